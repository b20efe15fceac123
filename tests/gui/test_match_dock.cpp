// The Match dock (issue 28, part 3) under a virtual X server, as a
// technician uses it: a measurement file simulated from a known recipe is
// read, one field ticked with bounds, the fit run on its thread (progress,
// cost curve), measured against fitted shown, and Accept edits the recipe
// in one undoable step saved as a new version with the fit recorded. A
// cancelled fit changes nothing; a choice that cannot run says which.

#include "ab_chart.h"
#include "author_setting.h"
#include "cost_curve.h"
#include "fit_runner.h"
#include "gui_test_main.h"
#include "inplane_plot.h"
#include "main_window.h"
#include "match_dock.h"
#include "plot_render_thread.h"
#include "plots_dock.h"
#include "replace_recipe_command.h"
#include "save_screenshot.h"
#include "spectra_plot.h"
#include "split_sphere.h"
#include "split_sphere_view.h"
#include "workstation_fixture.h"

#include "paintlab/database/database.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/measured/scattered_brdf.h"
#include "paintlab/engine/multiangle.h"

#include <QAction>
#include <QComboBox>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include <algorithm>
#include <cmath>
#include <memory>

using paintlab::gui::MainWindow;
using paintlab::gui::MatchDock;
namespace db = paintlab::db;

namespace {

using paintlab::test::kGuiWaitMs;
const QString kSolidRed = QStringLiteral("Solid red (iron oxide)");
const QString kBasecoat = QStringLiteral("layers[1].thickness_um");
constexpr double kTrueUm = 1.0;      // thin enough not to hide the primer: the thickness is determined
constexpr double kTemplateUm = 2.0;  // the first guess, 100 % off

// The recipe's multi-angle spectra at the standard preset, as an instrument
// would export them (spectra and CIELAB per geometry), without noise.
db::Measurement simulated(const paintlab::Recipe& truth) {
    const auto brdf =
        paintlab::computeLayeredBrdf(truth, paintlab::presetSettings(paintlab::Preset::Standard));
    const auto report = paintlab::multiAngleColours(brdf);
    db::Measurement m;
    m.name = "red panel 7";
    m.instrument = "simulated";
    const auto wavelengths = brdf.wavelengthsNm();
    m.wavelengths_nm.assign(wavelengths.begin(), wavelengths.end());
    for (const auto& c : report.colours)
        m.readings.push_back({45.0, c.aspecular_deg, c.lab.L, c.lab.a, c.lab.b, c.reflectance_factor});
    return m;
}

// A goniophotometer's BRDF samples (linear sRGB, 1/sr) of a recipe: light at
// theta_i 5..75 deg (step 10) and azimuth 0, view at theta_o 0..80 (step 5)
// and azimuth 0..180 (step 15): 8 x 17 x 13 = 1768 samples. At theta_i 45
// the plane of incidence holds the views at azimuth 0 and 180 (16 each, off
// the normal) and the 13 at the normal; within the plot's 2.5 deg of it
// also theta_o 5 at azimuths 15, 30, 150, 165 (the angle to the plane is
// asin(sin 5° sin 30°) = 2.498°): 49 samples.
constexpr std::size_t kDenseSamples = 1768;
constexpr std::size_t kDenseInPlane = 49;

db::Measurement brdfSamples(const paintlab::LayeredBrdf& brdf, const std::string& name, bool dense) {
    const auto weights = paintlab::bandColourWeights(brdf.wavelengthsNm());
    db::Measurement m;
    m.name = name;
    m.kind = db::MeasurementKind::Brdf;
    m.instrument = "simulated goniophotometer";
    m.channels = {"R", "G", "B"};
    std::vector<double> f(brdf.wavelengthsNm().size());
    for (int i = dense ? 0 : 4; i < (dense ? 8 : 5); ++i)  // sparse: the 45 deg incidence alone
        for (int o = 0; o <= 16; ++o)
            for (int p = 0; p <= 12; ++p) {
                db::BrdfSample s{5.0 + 10.0 * i, 0.0, 5.0 * o, 15.0 * p, {}};
                brdf.eval(paintlab::directionFromAnglesDeg(s.theta_i_deg, s.phi_i_deg),
                          paintlab::directionFromAnglesDeg(s.theta_o_deg, s.phi_o_deg), f);
                const paintlab::Rgb c = paintlab::weightedLinearSrgb(weights, f);
                // Out-of-gamut channels (below 0) at 0: a measurement is never negative.
                s.values = {std::max(c.r, 0.0), std::max(c.g, 0.0), std::max(c.b, 0.0)};
                m.samples.push_back(std::move(s));
            }
    return m;
}

}  // namespace

class MatchDockTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void aChoiceThatCannotRunSaysWhy();
    void cancelledFitChangesNothing();
    void fitRecoversTheThicknessAndAcceptIsOneUndoableSavedStep();
    void interpolatedSamplesShadeLikeTheirBrdf();
    void brdfMeasurementPointsAndSplitView();
    void runControlsShowWholeAtLaptopSize();
    void onlyTheInPlane45DegreeReadingsJoinTheFlopPlots();
    void cleanupTestCase();

private:
    MatchDock* dock() { return m_window->matchDock(); }
    double basecoatUm() { return m_window->document()->recipe().layers.at(1).thickness_um; }
    bool waitForFit();

    QTemporaryDir m_dir;
    QString m_db_file;
    std::unique_ptr<MainWindow> m_window;
};

void MatchDockTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    m_db_file = m_dir.path() + "/lab.db";
    m_window = paintlab::test::openWorkstation(paintlab::test::withoutScene(m_db_file));
    QVERIFY(m_window != nullptr);
    QVERIFY(m_window->selectRecipe(kSolidRed));
    // The template: the demo's solid red with a thin basecoat, saved as a version.
    paintlab::Recipe thin = m_window->document()->recipe();
    thin.layers.at(1).thickness_um = kTemplateUm;
    m_window->document()->undoStack()->push(
        new paintlab::gui::ReplaceRecipeCommand(m_window->document(), thin, "thin basecoat"));
    QVERIFY(m_window->saveVersionAs("thin basecoat template"));
    paintlab::Recipe truth = thin;
    truth.layers.at(1).thickness_um = kTrueUm;
    dock()->show();
    dock()->raise();
    dock()->addFileMeasurement(simulated(truth));
}

// Review item: at 1024 x 700 (the laptop layout: the dock a bottom tab) with
// a BRDF measurement chosen (the split pane takes room), the results pane
// scrolled and Cancel was clipped. Fit and Cancel must show whole, unscrolled.
// A 12-geometry instrument's file: the 15° rows and the out-of-plane
// 45as25az90 would sit on the plots' 45° in-plane flop at their aspecular
// angle alone (a zig-zag in the a*b* travel); the overlay keeps the six 45°
// in-plane readings. The geometry table names them in full (geometryName).
void MatchDockTest::onlyTheInPlane45DegreeReadingsJoinTheFlopPlots() {
    db::Measurement m = simulated(m_window->document()->recipe());
    m.name = "twelve-geometry panel";
    const db::MultiAngleReading in_plane = m.readings.at(2);  // 45as25
    db::MultiAngleReading out_of_plane = in_plane;
    out_of_plane.azimuth_deg = 90.0;
    db::MultiAngleReading low = in_plane;
    low.illumination_deg = 15.0;
    m.readings.push_back(out_of_plane);
    m.readings.push_back(low);
    dock()->addFileMeasurement(m);
    QCOMPARE(QString::fromStdString(dock()->chosenMeasurement()->name),
             QStringLiteral("twelve-geometry panel"));
    const auto report = dock()->measuredReport();
    QVERIFY(report.has_value());
    QCOMPARE(report->colours.size(), m.readings.size() - 2);
    for (std::size_t k = 0; k < report->colours.size(); ++k)
        QCOMPARE(report->colours[k].aspecular_deg, m.readings[k].aspecular_deg);
}

void MatchDockTest::runControlsShowWholeAtLaptopSize() {
    const QSize old_size = m_window->size();
    m_window->resize(1024, 700);
    QTRY_COMPARE_WITH_TIMEOUT(m_window->size(), QSize(1024, 700), kGuiWaitMs);
    m_window->findChild<QAction*>("reset_layout_action")->trigger();  // the default layout for this size
    dock()->show();
    dock()->raise();
    QVERIFY(QTest::qWaitFor(
        [&]() { return m_window->plotsDock()->brdf() != nullptr && !m_window->plotsDock()->computing(); },
        kGuiWaitMs));
    const std::shared_ptr<const paintlab::LayeredBrdf> brdf = m_window->plotsDock()->brdf();
    dock()->addFileMeasurement(brdfSamples(*brdf, "gonio laptop", true));
    QVERIFY(QTest::qWaitFor([&]() { return !dock()->splitView()->busy(); }, kGuiWaitMs));
    QTest::qWait(100);  // the layout settles
    for (QPushButton* button : {dock()->runButton(), dock()->cancelButton()}) {
        QVERIFY(button->isVisible());
        const QRect shown = button->visibleRegion().boundingRect();
        QVERIFY2(shown == button->rect(), qPrintable(QStringLiteral("%1 shows %2x%3 of %4x%5")
                                                         .arg(button->objectName())
                                                         .arg(shown.width())
                                                         .arg(shown.height())
                                                         .arg(button->width())
                                                         .arg(button->height())));
    }
    // Nor does the choices' pane scroll sideways (its parameter table's columns readable).
    auto* setup = dock()->findChild<QScrollArea*>("match_setup");
    QVERIFY(setup != nullptr);
    QVERIFY2(!setup->horizontalScrollBar()->isVisible(),
             qPrintable(QStringLiteral("the choices' pane is %1 px wide").arg(setup->width())));
    paintlab::test::saveScreenshot(m_window.get(), "match-laptop-1024x700");
    m_window->resize(old_size);
}

bool MatchDockTest::waitForFit() {
    // The runner's result arrives on the event loop; running() turns false with it.
    return QTest::qWaitFor([this]() { return !dock()->running(); }, kGuiWaitMs);
}

void MatchDockTest::aChoiceThatCannotRunSaysWhy() {
    dock()->measurementBox()->setCurrentIndex(0);  // "(choose a measurement)"
    dock()->run();
    QVERIFY(!dock()->running());
    QVERIFY2(dock()->status()->text().contains("measurement"), qPrintable(dock()->status()->text()));
    dock()->measurementBox()->setCurrentIndex(dock()->measurementBox()->count() - 1);
    dock()->run();  // nothing ticked
    QVERIFY(!dock()->running());
    QVERIFY2(dock()->status()->text().contains("tick at least one"), qPrintable(dock()->status()->text()));
    // A bound that is not a number names the field.
    QVERIFY(dock()->freeParameter(kBasecoat));
    auto* table = dock()->parameterTable();
    for (int row = 0; row < table->rowCount(); ++row)
        if (table->item(row, 0)->data(Qt::UserRole + 1).toString() == kBasecoat)
            table->item(row, 2)->setText("abc");
    dock()->run();
    QVERIFY(!dock()->running());
    QVERIFY2(dock()->status()->text().contains(kBasecoat), qPrintable(dock()->status()->text()));
}

void MatchDockTest::cancelledFitChangesNothing() {
    QVERIFY(dock()->freeParameter(kBasecoat, 0.3, 5.0));
    const paintlab::Recipe before = m_window->document()->recipe();
    const int undo_index = m_window->document()->undoStack()->index();
    QSignalSpy cancelled(dock()->runner(), &paintlab::gui::FitRunner::cancelled);
    dock()->run();
    QVERIFY(dock()->running());
    QVERIFY(!dock()->runButton()->isEnabled());
    dock()->cancel();
    QVERIFY(waitForFit());
    QCOMPARE(cancelled.count(), 1);
    QVERIFY(dock()->result() == nullptr);
    QVERIFY(!dock()->acceptButton()->isEnabled());
    QVERIFY(m_window->document()->recipe() == before);
    QCOMPARE(m_window->document()->undoStack()->index(), undo_index);
    QVERIFY2(dock()->status()->text().contains("cancelled"), qPrintable(dock()->status()->text()));
}

void MatchDockTest::fitRecoversTheThicknessAndAcceptIsOneUndoableSavedStep() {
    // The chosen panel is overlaid on the plots: its flop path and spectra.
    QCOMPARE(m_window->plotsDock()->comparisonLabel(), QStringLiteral("measured: red panel 7"));
    QVERIFY(m_window->plotsDock()->abChart()->hasComparison());
    QCOMPARE(m_window->plotsDock()->paintSpectra()->comparisonSpectra().size(), std::size_t{6});
    QVERIFY(dock()->freeParameter(kBasecoat, 0.3, 5.0));
    QSignalSpy progressed(dock()->runner(), &paintlab::gui::FitRunner::progressed);
    dock()->run();
    QVERIFY(waitForFit());
    QVERIFY2(dock()->result() != nullptr, qPrintable(dock()->status()->text()));
    QVERIFY(progressed.count() > 0);
    const auto& r = *dock()->result();
    QCOMPARE(r.parameters.size(), std::size_t{1});
    // Noise-free data at the report's own preset: the minimum is the truth,
    // 1 % is the solver's stopping tolerance, not the model's.
    QVERIFY2(std::abs(r.parameters[0].value - kTrueUm) < 0.01 * kTrueUm,
             qPrintable(QString::number(r.parameters[0].value)));
    QCOMPARE(dock()->geometryTable()->rowCount(), 6);
    QCOMPARE(dock()->resultTable()->rowCount(), 1);
    QVERIFY(dock()->acceptButton()->isEnabled());
    paintlab::test::saveScreenshot(dock(), "dock-match");

    // Accept: one undo step, saved as the next version, the fit recorded.
    const int version_before = m_window->document()->version();
    const int undo_index = m_window->document()->undoStack()->index();
    dock()->acceptButton()->click();
    QVERIFY(std::abs(basecoatUm() - r.parameters[0].value) < 1e-12);
    QCOMPARE(m_window->document()->version(), version_before + 1);
    QCOMPARE(m_window->document()->undoStack()->index(), undo_index + 1);
    {
        db::Database database = db::Database::open(m_db_file.toStdString());
        QVERIFY(db::findMeasurement(database, "red panel 7").has_value());
        const auto fits = db::fitsOfRecipe(database, kSolidRed.toStdString());
        QCOMPARE(fits.size(), std::size_t{1});
        QCOMPARE(fits[0].recipe_version, version_before + 1);
        QCOMPARE(fits[0].residuals.size(), std::size_t{6});
    }
    m_window->document()->undoStack()->undo();
    QCOMPARE(basecoatUm(), kTemplateUm);
}

void MatchDockTest::interpolatedSamplesShadeLikeTheirBrdf() {
    // The split view's left half shades interpolated samples: for samples of
    // a known BRDF it must look like that BRDF shaded directly (no display
    // involved: split_sphere.h).
    const auto brdf = paintlab::computeLayeredBrdf(m_window->document()->recipe(),
                                                   paintlab::presetSettings(paintlab::Preset::Standard));
    const db::Measurement m = brdfSamples(brdf, "truth", true);
    const paintlab::measured::ScatteredBrdf scattered(paintlab::gui::linearSrgbSamples(m), 3, "truth");
    constexpr int kPx = 64;
    const auto interpolated = paintlab::gui::renderSplitSphere(paintlab::gui::rgbBrdf(scattered),
                                                               paintlab::gui::rgbBrdf(brdf), kPx);
    const auto exact =
        paintlab::gui::renderSplitSphere(paintlab::gui::rgbBrdf(brdf), paintlab::gui::rgbBrdf(brdf), kPx);
    double diff = 0.0;
    double sum = 0.0;
    for (int y = 0; y < kPx; ++y)
        for (int x = 0; x < kPx / 2; ++x)
            for (int c = 0; c < 3; ++c) {
                const std::size_t i = 3 * static_cast<std::size_t>(y * kPx + x) + static_cast<std::size_t>(c);
                diff += static_cast<double>(std::abs(interpolated.rgb[i] - exact.rgb[i]));
                sum += static_cast<double>(exact.rgb[i]);
            }
    // Relative mean absolute difference over the measured half. The engine's
    // test bounds the interpolation at ~4 % RMS for a 12 deg lobe and 4,000
    // random samples; the solid red's lobe is broader and the grid's 5-15
    // deg steps resolve it: measured 1.1 %. 4 % allowed (the engine's
    // figure), well below a visible difference between the halves.
    qInfo("split sphere: interpolated against exact, relative mean difference %.4f", diff / sum);
    QVERIFY2(sum > 0.0 && diff / sum < 0.04, qPrintable(QString::number(diff / sum)));
    // The right half is the recipe itself in both images.
    for (int y = 0; y < kPx; ++y)
        for (int x = kPx / 2; x < kPx; ++x) {
            const std::size_t i = 3 * static_cast<std::size_t>(y * kPx + x);
            QCOMPARE(interpolated.rgb[i], exact.rgb[i]);
        }
}

void MatchDockTest::brdfMeasurementPointsAndSplitView() {
    auto* view = dock()->splitView();
    auto* points_plot = m_window->plotsDock()->inplanePlot();
    // The samples are of the BRDF the plots show (the render's), so the
    // points must lie on its curves.
    QVERIFY(QTest::qWaitFor(
        [&]() { return m_window->plotsDock()->brdf() != nullptr && !m_window->plotsDock()->computing(); },
        kGuiWaitMs));
    const std::shared_ptr<const paintlab::LayeredBrdf> shown =
        m_window->plotsDock()->brdf();  // kept alive here
    const paintlab::LayeredBrdf& brdf = *shown;
    // Sparse: the 45 deg incidence alone. Its in-plane samples are drawn; no sphere.
    dock()->addFileMeasurement(brdfSamples(brdf, "gonio sparse", false));
    QVERIFY(
        QTest::qWaitFor([&]() { return !view->busy() && !view->message().contains("Shading"); }, kGuiWaitMs));
    QVERIFY(!view->showsSpheres());
    QVERIFY2(view->message().contains("too sparse"), qPrintable(view->message()));
    qInfo("sparse: %s", qPrintable(view->message()));
    QCOMPARE(points_plot->measuredPointsDrawn(), kDenseInPlane);
    QCOMPARE(m_window->plot()->measuredPointsDrawn(), kDenseInPlane);
    paintlab::test::saveScreenshot(dock(), "dock-match-sparse");

    // Dense: the split view shades the samples against the edited recipe.
    dock()->addFileMeasurement(brdfSamples(brdf, "gonio dense", true));
    QVERIFY(QTest::qWaitFor([&]() { return view->showsSpheres() && !view->busy(); }, kGuiWaitMs));
    QCOMPARE(view->rightLabel(), QStringLiteral("recipe"));
    qInfo("split view: %d px sphere, %zu samples, shaded in %.2f s (worker), exposure %.2f EV",
          paintlab::gui::SplitSphereView::kSpherePx, kDenseSamples, view->seconds(), view->exposureEv());
    QCOMPARE(points_plot->measuredSamples().total, kDenseSamples);
    QCOMPARE(points_plot->measuredPointsDrawn(), kDenseInPlane);
    // Every drawn point is a sample of the 45 deg light in its plane: pi f
    // equals the recipe's own curve at that view angle (the samples are
    // the recipe's f; the curve is on a 2.5 deg grid, the views on 5 deg).
    const auto& curve = points_plot->curve();
    const auto& pts = points_plot->measuredSamples();
    for (std::size_t k = 0; k < pts.view_deg.size(); ++k) {
        const auto at = std::find_if(curve.view_deg.begin(), curve.view_deg.end(),
                                     [&](double v) { return std::abs(v - pts.view_deg[k]) < 1e-9; });
        if (at == curve.view_deg.end()) continue;  // beyond the curve's 85 deg
        const auto i = static_cast<std::size_t>(at - curve.view_deg.begin());
        // The same BRDF: the samples from its eval(), the curve from the
        // plot's own Fourier sums; they agreed to 2e-5 relative (measured).
        // 1e-3 allows that; a point from the other side of the plane or
        // another incidence is off by per cents.
        QVERIFY2(std::abs(pts.r[k] - std::max(curve.r[i], 0.0)) <= 1e-3 * curve.r[i],
                 qPrintable(
                     QStringLiteral("%1 deg: %2 vs %3").arg(pts.view_deg[k]).arg(pts.r[k]).arg(curve.r[i])));
    }
    QVERIFY(points_plot->measuredCaption().contains(QStringLiteral("49 of the 1768 samples")));
    paintlab::test::saveScreenshot(dock(), "dock-match-split");
    {
        // The central in-plane plot (45 deg alone) draws them too, with a legend line per channel.
        QWidget* central = m_window->plot()->parentWidget();
        while (central != nullptr && qobject_cast<QDockWidget*>(central) == nullptr)
            central = central->parentWidget();
        QVERIFY(central != nullptr);
        central->show();
        central->raise();
        QTest::qWait(300);
        paintlab::gui::PlotRenderThread::instance().settle();
        const auto layout = m_window->plot()->chartLayout();
        QVERIFY2(layout.legend_labels.contains(QStringLiteral("R measured (gonio dense, light at 45 deg)")),
                 qPrintable(layout.legend_labels.join(" | ")));
        paintlab::test::saveScreenshot(m_window->plot(), "inplane-central-measured");
    }
    m_window->plotsDock()->show();
    m_window->plotsDock()->raise();
    m_window->plotsDock()->tabs()->setCurrentWidget(m_window->plotsDock()->tabs()->widget(1));
    QTest::qWait(300);
    paintlab::gui::PlotRenderThread::instance().settle();
    paintlab::test::saveScreenshot(m_window->plotsDock(), "plots-inplane-measured");

    // Choosing another measurement while the split view shades stops it:
    // the running shading is cancelled and never shown.
    dock()->measurementBox()->setCurrentIndex(0);
    dock()->measurementBox()->setCurrentIndex(
        dock()->measurementBox()->findText("gonio dense", Qt::MatchStartsWith));
    QVERIFY(view->busy());
    dock()->measurementBox()->setCurrentIndex(
        dock()->measurementBox()->findText("red panel 7", Qt::MatchStartsWith));
    QVERIFY(view->isHidden());
    QElapsedTimer stopping;
    stopping.start();
    QVERIFY(QTest::qWaitFor([&]() { return !view->busy(); }, kGuiWaitMs));
    qInfo("split view: cancelled shading stopped after %lld ms", stopping.elapsed());
    QVERIFY(!view->showsSpheres());
    QCOMPARE(points_plot->measuredPointsDrawn(), std::size_t{0});

    // Fitted (to the sparse set: a fit to the dense one takes a minute on 2
    // cores, too long for CI): the plots' dashed curves become the fit's,
    // the split view still says why it cannot shade.
    dock()->measurementBox()->setCurrentIndex(
        dock()->measurementBox()->findText("gonio sparse", Qt::MatchStartsWith));
    QCOMPARE(dock()->measuredName(), QStringLiteral("gonio sparse"));
    dock()->freeParameter(kBasecoat, 0.3, 5.0);
    m_window->findChild<QSpinBox*>("match_starts")->setValue(1);
    dock()->run();
    QVERIFY(waitForFit());
    QVERIFY2(dock()->result() != nullptr, qPrintable(dock()->status()->text()));
    qInfo("BRDF fit: %ld evaluations, %.1f s", dock()->result()->evaluations, dock()->result()->seconds);
    QVERIFY(QTest::qWaitFor([&]() { return points_plot->hasComparison(); }, kGuiWaitMs));
    QCOMPARE(m_window->plotsDock()->comparisonLabel(), QStringLiteral("fitted: gonio sparse"));
    QVERIFY(m_window->plot()->hasComparison());
    QCOMPARE(points_plot->measuredPointsDrawn(), kDenseInPlane);
    QVERIFY2(view->message().contains("too sparse"), qPrintable(view->message()));
    QTest::qWait(300);
    paintlab::gui::PlotRenderThread::instance().settle();
    paintlab::test::saveScreenshot(m_window->plotsDock(), "plots-inplane-fitted");
}

void MatchDockTest::cleanupTestCase() {
    m_window->document()->undoStack()->clear();  // no unsaved-edits question on close
    m_window.reset();
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<MatchDockTest>(argc, argv, "paintlab-match-test");
}

#include "test_match_dock.moc"
