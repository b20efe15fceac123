// The workstation under a virtual X server (tests/gui/CMakeLists.txt runs it
// in xvfb-run): it starts on the demo database, shows plots and a relit image
// of the pearlescent demo, follows a flake-concentration slider, undoes
// exactly, saves a version, reports a malformed recipe file in a dialog, and
// survives 200 rapid edits with a final image equal to a fresh render; the
// accuracy dock lists the effect plan, and turning the plan off changes what
// is computed; the render dock compares the edited recipe with a saved
// version side by side and split, pixel for pixel equal to single renders.
//
// The scene is the demo car scene at 64 x 36 pixels (written by the test) so
// that tracing and relighting take well under a second even under ASan.
// Times are not asserted (speed is measured in benchmarks, docs/PERFORMANCE.md);
// every wait has a generous timeout so a loaded CI machine does not fail it.

#include "test_workstation.h"
#include "gui_test_main.h"

#include "accuracy_dock.h"
#include "author_setting.h"
#include "comparison_view.h"
#include "inplane_plot.h"
#include "main_window.h"
#include "plots_dock.h"
#include "recipe_editor_dock.h"
#include "render_dock.h"
#include "screenshot_baseline.h"
#include "versions_dock.h"
#include "workstation_fixture.h"

#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/planned_relight.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/scene.h"

#include "paintlab/database/database.h"
#include "paintlab/database/recipes.h"

#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QListWidget>
#include <QMessageBox>
#include <QPainter>
#include <QPushButton>
#include <QRandomGenerator>
#include <QSignalSpy>
#include <QSlider>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QThread>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

using paintlab::gui::MainWindow;
using paintlab::test::kPearl;
using paintlab::test::kWaitMs;

namespace {

// Times every event the GUI thread dispatches while recording, so the stall
// test can say which receiver and event type held the thread (outermost
// dispatch only: a paint inside a timer's handler counts once, as the timer).
class TimedApplication : public QApplication {
public:
    using QApplication::QApplication;
    struct Slow {
        double ms;
        QString what;
    };
    bool notify(QObject* receiver, QEvent* event) override {
        // notify() runs for every thread's events: only the GUI thread's are
        // timed (the plot render thread's draws are meant to be long).
        if (!recording || depth > 0 || QThread::currentThread() != thread())
            return QApplication::notify(receiver, event);
        ++depth;
        // Taken before the dispatch (it may delete the receiver), cheaply: the
        // text is made only for the slow ones, not for every event timed.
        const char* const type_name = receiver->metaObject()->className();
        const QString object_name = receiver->objectName();  // implicitly shared: no copy
        const int type = static_cast<int>(event->type());
        QElapsedTimer timer;
        timer.start();
        const bool handled = QApplication::notify(receiver, event);
        --depth;
        const double ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
        if (ms > 20.0)
            slow.push_back({ms, QStringLiteral("%1 '%2', event %3")
                                    .arg(QString::fromLatin1(type_name), object_name)
                                    .arg(type)});
        return handled;
    }
    bool recording = false;
    int depth = 0;
    std::vector<Slow> slow;  // dispatches over 20 ms
};

TimedApplication* timedApp() { return static_cast<TimedApplication*>(QCoreApplication::instance()); }

}  // namespace

void WorkstationTest::waitIdle() {
    // Idle and not tracing: the scheduler has nothing computing or pending.
    QTRY_VERIFY_WITH_TIMEOUT(m_window->scheduler()->idle() && m_window->scheduler()->rayMap() != nullptr,
                             kWaitMs);
}

void WorkstationTest::waitComparison() {
    waitIdle();
    QTRY_VERIFY_WITH_TIMEOUT(m_window->comparisonScheduler()->idle() &&
                                 !m_window->renderDock()->comparisonImage().isNull(),
                             kWaitMs);
}

paintlab::gui::RenderResult WorkstationTest::singleRender(const paintlab::Recipe& recipe,
                                                          paintlab::Preset preset) {
    paintlab::gui::RenderScheduler scheduler;
    scheduler.setRayMap(m_window->scheduler()->rayMap());
    scheduler.setExposure(m_window->scheduler()->exposure());
    scheduler.setFollowPlan(m_window->scheduler()->followPlan());
    QSignalSpy rendered(&scheduler, &paintlab::gui::RenderScheduler::finished);
    scheduler.request(recipe, preset);
    if (!rendered.wait(kWaitMs)) return {};
    return rendered.takeFirst().at(0).value<paintlab::gui::RenderResult>();
}

paintlab::gui::RenderResult WorkstationTest::renderNow() {
    waitIdle();
    QSignalSpy rendered(m_window->scheduler(), &paintlab::gui::RenderScheduler::finished);
    m_window->document()->settle();  // announces the recipe again: a new request as the GUI makes it
    if (!rendered.wait(kWaitMs)) return {};
    waitIdle();
    return rendered.takeLast().at(0).value<paintlab::gui::RenderResult>();
}

void WorkstationTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    const QString scene_file = paintlab::test::writeTinyDemoScene(m_dir.path());
    paintlab::gui::WorkstationOptions options;
    options.database = (m_dir.path() + "/lab.db").toStdString();
    options.scene = scene_file.toStdString();
    options.raymap_follows_view = false;  // the tiny scene as it is
    options.refine_ray_map = false;       // the cases compare renders of one fixed map
    m_window = paintlab::test::openWorkstation(options, QSize(1400, 900));  // fixed for the baselines
    QVERIFY(m_window != nullptr);
}

void WorkstationTest::startsOnTheDemoDatabase() {
    // The five demo recipes of packaging/demo/recipes, created on first use.
    QCOMPARE(m_window->recipeList()->count(), 5);
}

void WorkstationTest::pearlescentShowsPlotAndImage() {
    QVERIFY(m_window->selectRecipe(kPearl));
    QTRY_VERIFY_WITH_TIMEOUT(!m_window->renderDock()->image().isNull(), kWaitMs);
    waitIdle();
    QCOMPARE(m_window->renderDock()->image().width(), 64);
    const auto& curve = m_window->plot()->curve();
    QVERIFY(!curve.view_deg.empty());
    // A blue pearl: blue above red at the specular peak (view +45 degrees).
    const auto peak = static_cast<std::size_t>(
        std::distance(curve.view_deg.begin(), std::find(curve.view_deg.begin(), curve.view_deg.end(), 45.0)));
    QVERIFY(peak < curve.view_deg.size());
    QVERIFY(curve.b[peak] > curve.r[peak]);
}

// The main window and every dock, on the pearlescent demo, against the
// baselines in tests/gui/baselines (screenshot_baseline.h). Threshold: mean
// SSIM 0.98. Two runs on one machine give 0.993-1.000 (the render, plots and
// layout are deterministic; the temporary database's path changes, and the
// timing figures are masked); two Debian 12 machines with the same packages draw the same
// fonts. The negative control below, the central plot blanked, gives 0.962
// with all docks shown: the threshold catches a blank plot.
void WorkstationTest::screenshotsMatchBaselines() {
    waitIdle();
    // The measured times are the one thing that differs from run to run (and
    // by 4x under the sanitizers): shown as "#.# ms" in the screenshots.
    QTest::qWait(200);  // let the last repaint of the plots land
    paintlab::test::maskMeasuredTimes(*m_window);
    constexpr double kThreshold = 0.98;
    auto check = [&](QWidget& widget, const QString& name) {
        auto result = paintlab::test::compareWithBaseline(widget, name, kThreshold);
        qInfo("%s", qPrintable(result.message));
        if (!result.ok) {
            // Seen twice in ~35 runs, both under a heavy compile beside the
            // test, for the Accuracy dock only (0.952, not reproduced since):
            // a second look after the pending layout and paint events, with
            // what the widget showed printed, tells a transient state from a
            // real difference.
            qInfo("  %s below the threshold; what it shows:", qPrintable(name));
            // What the widget showed, for a failure seen only once in a while
            // (the screenshot itself is overwritten by the next run).
            for (const QLabel* label : widget.findChildren<QLabel*>())
                if (label->isVisible())
                    qInfo("  label '%s': %s", qPrintable(label->objectName()), qPrintable(label->text()));
            for (const QTableWidget* table : widget.findChildren<QTableWidget*>())
                for (int row = 0; row < table->rowCount(); ++row)
                    for (int col = 0; col < table->columnCount(); ++col)
                        if (table->item(row, col) != nullptr)
                            qInfo("  table '%s' (%d, %d): %s", qPrintable(table->objectName()), row, col,
                                  qPrintable(table->item(row, col)->text()));
            QFile::remove("screenshots/" + name + "-first-look.png");
            QFile::copy("screenshots/" + name + ".png", "screenshots/" + name + "-first-look.png");
            QTest::qWait(500);
            result = paintlab::test::compareWithBaseline(widget, name, kThreshold);
            qInfo("  second look: %s", qPrintable(result.message));
        }
        QVERIFY2(result.ok, qPrintable(result.message));
    };
    check(*m_window, QStringLiteral("main-window"));
    if (qEnvironmentVariableIntValue("PAINTLAB_UPDATE_BASELINES") != 1) {
        QImage blank_plot = m_window->grab().toImage();
        QPainter(&blank_plot).fillRect(m_window->centralWidget()->geometry(), Qt::white);
        const double ssim = paintlab::test::meanSsim(
            paintlab::test::greyOf(blank_plot),
            paintlab::test::greyOf(QImage(QStringLiteral(PAINTLAB_GUI_BASELINE_DIR "/main-window.png"))));
        qInfo("negative control, plot blanked: mean SSIM %.4f", ssim);
        QVERIFY2(ssim < kThreshold, "a blank plot must fail the screenshot comparison");
    }
    for (QDockWidget* dock : m_window->findChildren<QDockWidget*>()) {
        if (!dock->isVisible() || dock->objectName().isEmpty()) continue;
        check(*dock, QStringLiteral("dock-") + dock->objectName());
    }
}

void WorkstationTest::sliderChangesPlotAndRenderAndUndoRestoresExactly() {
    waitIdle();
    const QImage before = m_window->renderDock()->image();
    const auto curve_before = m_window->plot()->curve().y;
    QSlider* slider = m_window->editorDock()->sliderFor("volume_fraction");  // the pearl flakes
    QVERIFY(slider != nullptr);
    QSignalSpy rendered(m_window->scheduler(), &paintlab::gui::RenderScheduler::finished);
    slider->setValue(slider->value() / 2 + 10);
    QTRY_VERIFY_WITH_TIMEOUT(rendered.count() >= 1, kWaitMs);
    waitIdle();
    QVERIFY(m_window->renderDock()->image() != before);
    QVERIFY(m_window->plot()->curve().y != curve_before);

    m_window->document()->undoStack()->undo();
    waitIdle();
    // Same recipe, same deterministic fast model and relight: the same pixels.
    QVERIFY(m_window->renderDock()->image() == before);
    QVERIFY(m_window->plot()->curve().y == curve_before);
}

void WorkstationTest::savingCreatesANewVersion() {
    waitIdle();
    QSlider* slider = m_window->editorDock()->sliderFor("thickness_um");
    QVERIFY(slider != nullptr);
    slider->setValue(slider->value() + 50);
    QVERIFY(m_window->saveVersionAs(QStringLiteral("thicker clear coat (GUI test)")));
    auto db = paintlab::db::Database::open((m_dir.path() + "/lab.db").toStdString());
    const auto history = paintlab::db::recipeHistory(db, kPearl.toStdString());
    QCOMPARE(static_cast<int>(history.size()), 2);
    QCOMPARE(QString::fromStdString(history.back().note), QStringLiteral("thicker clear coat (GUI test)"));
}

void WorkstationTest::malformedRecipeFileGivesAnErrorDialog() {
    const QString bad = m_dir.path() + "/negative.json";
    QFile::copy(QStringLiteral(PAINTLAB_TEST_DATA_DIR) + "/bad_recipes/negative_thickness.json", bad);
    const paintlab::Recipe kept = m_window->document()->recipe();
    QVERIFY(!m_window->openRecipeFile(bad));
    auto* dialog = m_window->findChild<QMessageBox*>(QStringLiteral("error_dialog"));
    QVERIFY(dialog != nullptr);
    QVERIFY2(dialog->text().contains(QStringLiteral("negative.json")), qPrintable(dialog->text()));
    QVERIFY2(dialog->text().contains(QStringLiteral("thickness")), qPrintable(dialog->text()));
    QVERIFY(m_window->document()->recipe() == kept);  // the recipe being edited is untouched
    dialog->close();
}

void WorkstationTest::rapidEditsEndOnTheFinalRecipe() {
    waitIdle();
    QSlider* slider = m_window->editorDock()->sliderFor("volume_fraction");
    QVERIFY(slider != nullptr);
    QRandomGenerator random(7);
    for (int i = 0; i < 200; ++i) {
        slider->setValue(random.bounded(slider->minimum(), slider->maximum() + 1));
        if (i % 10 == 0) QCoreApplication::processEvents();
    }
    waitIdle();
    const QImage last = m_window->renderDock()->image();
    // A fresh render of the final recipe gives the same image.
    QSignalSpy rendered(m_window->scheduler(), &paintlab::gui::RenderScheduler::finished);
    m_window->scheduler()->request(m_window->document()->recipe(), paintlab::Preset::Standard);
    QTRY_VERIFY_WITH_TIMEOUT(rendered.count() == 1, kWaitMs);
    const auto result = rendered.takeFirst().at(0).value<paintlab::gui::RenderResult>();
    QVERIFY(result.image == last);
}

// A slider dragged at 60 edits per second for two seconds, then released,
// while a 5 ms timer on the GUI thread records how late it fires: its longest
// gap is how long the GUI thread was blocked (edit handling, plot and image
// updates; the fast model and relight run on the worker). The figures are
// printed for docs/PERFORMANCE.md, not asserted (speed is measured, not
// tested); the test fails only on a freeze: 10 s, far above any scheduling
// delay on a loaded machine, is what the fast model or a trace on the GUI
// thread would cost under ASan.
void WorkstationTest::draggingNeverFreezesTheGuiThread() {
    waitIdle();
    QSlider* slider = m_window->editorDock()->sliderFor("volume_fraction");
    QVERIFY(slider != nullptr);
    QElapsedTimer clock;
    clock.start();
    qint64 last_ms = 0;
    std::vector<qint64> gaps_ms;
    QTimer watchdog;
    watchdog.setInterval(5);
    double longest_plot_paint_ms = 0.0;
    double longest_plot_show_ms = 0.0;
    connect(&watchdog, &QTimer::timeout, this, [&]() {
        longest_plot_paint_ms = std::max(longest_plot_paint_ms, m_window->plot()->lastPaintMs());
        longest_plot_show_ms = std::max(longest_plot_show_ms, m_window->plot()->lastShowMs());
        const qint64 now = clock.elapsed();
        gaps_ms.push_back(now - last_ms);
        last_ms = now;
    });
    int edits = 0;
    QTimer drag;
    drag.setInterval(16);
    const int range = slider->maximum() - slider->minimum() + 1;
    connect(&drag, &QTimer::timeout, this, [&]() {
        slider->setValue(slider->minimum() + (edits * 37) % range);
        ++edits;
    });
    slider->setSliderDown(true);  // dragging: the preview preset
    timedApp()->slow.clear();
    timedApp()->recording = true;
    watchdog.start();
    drag.start();
    QTest::qWait(2000);
    drag.stop();
    slider->setSliderDown(false);  // released: the standard preset
    waitIdle();
    watchdog.stop();
    timedApp()->recording = false;
    auto slow = timedApp()->slow;
    std::sort(slow.begin(), slow.end(), [](const auto& a, const auto& b) { return a.ms > b.ms; });
    for (std::size_t i = 0; i < std::min<std::size_t>(slow.size(), 8); ++i)
        qInfo("  slow dispatch %.1f ms: %s", slow[i].ms, qPrintable(slow[i].what));
    qInfo(
        "  the central in-plane plot: VTK draw on the plot render thread at most %.1f ms, showing the image "
        "on the GUI thread at most %.1f ms",
        longest_plot_paint_ms, longest_plot_show_ms);
    QVERIFY(!gaps_ms.empty());
    std::sort(gaps_ms.begin(), gaps_ms.end());
    const qint64 p99 = gaps_ms[gaps_ms.size() * 99 / 100];
    qInfo("GUI thread while dragging: %d edits, %zu timer ticks, longest stall %lld ms, 99th percentile %lld "
          "ms",
          edits, gaps_ms.size(), static_cast<long long>(gaps_ms.back()), static_cast<long long>(p99));
    QVERIFY2(gaps_ms.back() < 10000, "the GUI thread froze");
}

// The pearl in the demo scene: one row per decision of the planner, each
// with what runs, the error it accepts and a reason; the interference flakes
// make the interference optics run.
void WorkstationTest::accuracyDockListsThePlanWithReasons() {
    QVERIFY(m_window->selectRecipe(kPearl));
    const paintlab::gui::RenderResult result = renderNow();
    QVERIFY(result.follow_plan);
    QVERIFY(result.plan.has_value());
    QTableWidget* table = m_window->accuracyDock()->planTable();
    QCOMPARE(table->rowCount(), static_cast<int>(result.plan->decisions.size()));
    QStringList effects;
    for (int row = 0; row < table->rowCount(); ++row) {
        effects << table->item(row, 0)->text();
        QVERIFY2(!table->item(row, 1)->text().isEmpty(), qPrintable(effects.back()));
        bool number = false;
        table->item(row, 2)->text().toDouble(&number);
        QVERIFY2(number, qPrintable(table->item(row, 2)->text()));
        QVERIFY2(table->item(row, 3)->text().size() > 10, qPrintable(effects.back()));
    }
    QCOMPARE(effects, QStringList({"interference", "sparkle", "angular", "bands", "slices", "full_model"}));
    QCOMPARE(table->item(0, 1)->text(), QStringLiteral("on"));
    QVERIFY2(table->item(0, 3)->text().contains(QStringLiteral("interference flake")),
             qPrintable(table->item(0, 3)->text()));
    const QString summary = m_window->accuracyDock()->planSummary()->text();
    QVERIFY2(summary.contains(QStringLiteral("ray map")) &&
                 summary.contains(QStringLiteral("expected error")),
             qPrintable(summary));
    // What ran is what the plan says, as the CLI's relight --plan runs it.
    const paintlab::FastModelSettings ran = result.brdf->settings();
    const paintlab::FastModelSettings planned = paintlab::raymaps::plannedSettings(*result.plan);
    QCOMPARE(ran.orders, planned.orders);
    QCOMPARE(ran.bands, planned.bands);
    QCOMPARE(ran.slices, planned.slices);
    QCOMPARE(result.sparkle, result.plan->sparkle);
    qInfo("pearl, standard, 64 x 36: plan %.1f ms, fast model %.1f ms, relight tables %.1f ms, relight %.2f "
          "ms, "
          "sparkle %s",
          result.plan_ms, result.brdf_ms, result.tables_ms, result.relight_ms, result.sparkle ? "on" : "off");

    // Without a scene: the plan for the BRDF alone (a collimated light,
    // spectral): no order or band dropped, no image to draw glints on.
    paintlab::gui::RenderScheduler brdf_only;
    QSignalSpy done(&brdf_only, &paintlab::gui::RenderScheduler::finished);
    brdf_only.request(m_window->document()->recipe(), paintlab::Preset::Standard);
    QVERIFY(done.wait(kWaitMs));
    const auto alone = done.takeFirst().at(0).value<paintlab::gui::RenderResult>();
    QVERIFY(alone.plan.has_value());
    QVERIFY(alone.image.isNull());
    QVERIFY(!alone.sparkle);
    QVERIFY2(alone.plan_scene.contains(QStringLiteral("BRDF alone")), qPrintable(alone.plan_scene));
    const paintlab::FastModelSettings standard = paintlab::presetSettings(paintlab::Preset::Standard);
    QCOMPARE(alone.brdf->settings().orders, standard.orders);
    QCOMPARE(alone.brdf->settings().bands, standard.bands);
    paintlab::gui::AccuracyDock dock;
    dock.showResult(alone);
    QCOMPARE(dock.planTable()->rowCount(), static_cast<int>(alone.plan->decisions.size()));
    QVERIFY2(dock.planSummary()->text().contains(QStringLiteral("BRDF alone")),
             qPrintable(dock.planSummary()->text()));
}

// The silver metallic in the demo scene: the plan drops bands (smooth
// spectra under RGB lighting; at this tiny image's footprints it skips the
// glints too); the plain preset computes all of the preset's bands and no
// sparkle.
void WorkstationTest::turningThePlanOffChangesWhatIsComputed() {
    QVERIFY(m_window->selectRecipe(QStringLiteral("Silver metallic (aluminium flakes)")));
    const paintlab::gui::RenderResult planned = renderNow();
    QVERIFY(planned.plan.has_value());
    const paintlab::FastModelSettings preset = paintlab::presetSettings(planned.preset);
    QVERIFY2(planned.brdf->settings().bands < preset.bands,
             qPrintable(QString::number(planned.brdf->settings().bands)));
    QCOMPARE(planned.sparkle, planned.plan->sparkle);

    m_window->accuracyDock()->setFollowPlan(false);  // requests a render itself
    waitIdle();
    const paintlab::gui::RenderResult plain = renderNow();
    QVERIFY(!plain.follow_plan);
    QVERIFY(!plain.plan.has_value());
    QVERIFY(!plain.sparkle);
    QCOMPARE(plain.brdf->settings().bands, preset.bands);
    QVERIFY(plain.image != planned.image);
    QVERIFY(m_window->accuracyDock()->planTable()->rowCount() == 0);
    QVERIFY2(m_window->accuracyDock()->planSummary()->text().contains(QStringLiteral("off")),
             qPrintable(m_window->accuracyDock()->planSummary()->text()));

    m_window->accuracyDock()->setFollowPlan(true);
    waitIdle();
    QCOMPARE(renderNow().brdf->settings().bands, planned.brdf->settings().bands);
}

// A close-up where the plan keeps the glints (a panel 10 cm away, ~50 µm
// pixels, one sun, as tests/raymaps/test_sparkle_pass.cpp): the silver
// metallic's preview leaves the sparkle pass for the standard render after
// the release (the pass cost 12-40x the relight on the demo scene), which draws it.
void WorkstationTest::previewsLeaveTheGlintsForTheRelease() {
    const QString scene_file = m_dir.path() + "/scenes/panel.json";
    std::ofstream(scene_file.toStdString()) << R"({"schema_version": 1,
      "camera": {"position": [0, 0.06, 0.08], "look_at": [0, 0, 0], "vertical_fov_deg": 0.917, "width": 32, "height": 32},
      "environment": {"intensity": 0.2},
      "lights": [{"type": "sun", "direction": [0.1, 0.6, -0.8], "irradiance": [3, 3, 3]}],
      "materials": [{"name": "paint", "kind": "paint"}],
      "objects": [{"name": "panel", "plane": {"size": 1}, "material": "paint"}]})";
    paintlab::raymaps::RayMapSettings settings;
    settings.aa_samples = 1;
    settings.light_rays = 16;
    settings.bake_paths = 1;
    const std::filesystem::path map_file = (m_dir.path() + "/panel.prm").toStdString();
    paintlab::raymaps::buildRayMap(paintlab::raymaps::loadSceneFile(scene_file.toStdString()), settings,
                                   map_file);
    paintlab::gui::RenderScheduler scheduler;
    scheduler.setRayMap(
        std::shared_ptr<const paintlab::raymaps::RayMap>(paintlab::raymaps::RayMap::open(map_file)));
    scheduler.setFollowPlan(true);
    const paintlab::Recipe silver = paintlab::loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) /
                                                             "recipes" / "silver-metallic.json");
    const auto render = [&](paintlab::Preset preset) {
        QSignalSpy rendered(&scheduler, &paintlab::gui::RenderScheduler::finished);
        scheduler.request(silver, preset);
        if (!rendered.wait(kWaitMs)) return paintlab::gui::RenderResult{};
        return rendered.takeFirst().at(0).value<paintlab::gui::RenderResult>();
    };
    const paintlab::gui::RenderResult preview = render(paintlab::Preset::Preview);
    QVERIFY(preview.plan.has_value() && preview.plan->sparkle);
    QVERIFY(!preview.sparkle && preview.sparkle_deferred);
    const paintlab::gui::RenderResult standard = render(paintlab::Preset::Standard);
    QVERIFY(standard.plan.has_value() && standard.plan->sparkle);
    QVERIFY(standard.sparkle && !standard.sparkle_deferred);
    qInfo("close-up, silver metallic: preview %.1f ms without the sparkle pass; standard %.1f ms with it "
          "(sparkle %.1f ms)",
          preview.plan_ms + preview.brdf_ms + preview.tables_ms + preview.relight_ms,
          standard.plan_ms + standard.brdf_ms + standard.tables_ms + standard.relight_ms +
              standard.sparkle_ms,
          standard.sparkle_ms);
}

void WorkstationTest::cleanupTestCase() { m_window.reset(); }

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<WorkstationTest, TimedApplication>(argc, argv, "PaintLab-test");
}
