// The Plots dock's full-model overlay under a virtual X server
// (tests/gui/CMakeLists.txt runs this in xvfb-run): a Monte Carlo run with a
// budget is overlaid on the fast model's curves, labelled with its paths and
// the recipe it ran on, and lies near the fast model; Cancel stops it within
// a second, the newest request wins, and an error names the field. Times are
// printed, not asserted (docs/PERFORMANCE.md).

#include "gui_test_main.h"
#include "plot_test_support.h"
#include "plots_dock.h"

#include "ab_chart.h"
#include "inplane_plot.h"
#include "spectra_plot.h"

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <map>
#include <memory>

using namespace paintlab;
using namespace paintlab::gui;
using paintlab::test::Csv;
using paintlab::test::readCsv;
using paintlab::test::silverRecipe;

namespace {

constexpr int kWaitMs = test::kGuiWaitMs;

}  // namespace

class FullModelOverlayTest : public QObject {
    Q_OBJECT
private slots:
    void fullModelOverlayIsLabelledAndNearTheFastModel();
    void fullModelCancelStopsTheRun();
    void fullModelNewestRequestWins();
    void fullModelErrorNamesTheField();

private:
    QTemporaryDir m_dir;
};

namespace {

// A Plots dock of its own (the main window's is the same class) with the
// silver metallic's preview BRDF and recipe.
std::unique_ptr<PlotsDock> silverDock(const Recipe& recipe) {
    auto dock = std::make_unique<PlotsDock>();
    dock->resize(1200, 500);
    dock->show();
    dock->setRecipe(recipe);
    dock->setBrdf(
        std::make_shared<const LayeredBrdf>(computeLayeredBrdf(recipe, presetSettings(Preset::Preview))));
    return dock;
}

void clickButton(PlotsDock& dock, const char* name) {
    auto* button = dock.findChild<QPushButton*>(QString::fromLatin1(name));
    QVERIFY(button != nullptr);
    QTest::mouseClick(button, Qt::LeftButton);
}

}  // namespace

void FullModelOverlayTest::fullModelOverlayIsLabelledAndNearTheFastModel() {
    const Recipe silver = silverRecipe();
    auto dock = silverDock(silver);
    QTRY_VERIFY_WITH_TIMEOUT(dock->brdf() != nullptr && !dock->computing(), kWaitMs);
    // 3 s, not 1: a 1 s run under CI's load kept ~26k paths, where the check
    // below fails on most seeds; 3 s beside four busy processes on two cores
    // kept 145-222k (docs/PERFORMANCE.md, "The full-model overlay's budget").
    dock->fullModelSeconds()->setValue(3);
    QSignalSpy ended(dock.get(), &PlotsDock::fullModelEnded);
    QElapsedTimer timer;
    timer.start();
    clickButton(*dock, "plots_full_model");
    QVERIFY(dock->fullModelRunning());
    // An edit while it runs: the run keeps its recipe, and the label says so.
    Recipe edited = silver;
    edited.layers[0].thickness_um *= 1.1;
    dock->setRecipe(edited);
    QTRY_VERIFY_WITH_TIMEOUT(ended.count() == 1, kWaitMs);
    QCOMPARE(ended.at(0).at(0).toBool(), true);
    QTRY_VERIFY_WITH_TIMEOUT(!dock->computing() && dock->inplanePlot()->hasComparison() &&
                                 dock->abChart()->hasComparison(),
                             kWaitMs);
    // Issue 27 item 10: also on the Paint spectra (the tab a run may be started
    // from): the six geometries' spectra of the full model, dashed.
    QCOMPARE(dock->paintSpectra()->comparisonSpectra().size(), std::size_t{6});
    QVERIFY(dock->status()->text().contains(QStringLiteral("full model")));
    qInfo("full model, 3 s budget: overlay after %.1f s (%s)", static_cast<double>(timer.elapsed()) * 1e-3,
          qPrintable(dock->fullModelLabel()));
    const QString label = dock->fullModelLabel();
    QVERIFY2(label.startsWith(QStringLiteral("full model (Monte Carlo, ")) && label.contains(" paths, ") &&
                 label.contains(QStringLiteral(" of the recipe as at ")),
             qPrintable(label));
    const QString inplane = m_dir.filePath("full_inplane.csv");
    const QString ab = m_dir.filePath("full_ab.csv");
    QVERIFY(dock->inplanePlot()->exportCsv(inplane));
    QVERIFY(dock->abChart()->exportCsv(ab));
    const Csv in_csv = readCsv(inplane);
    const Csv ab_csv = readCsv(ab);
    std::size_t full_rows = 0;
    std::map<double, double> fast_y, full_y;  // the 45 degree curve, by view angle
    for (std::size_t k = 0; k < in_csv.rows.size(); ++k) {
        const QString& series = in_csv.rows[k][0];
        QVERIFY2(series == QStringLiteral("current") || series == label, qPrintable(series));
        if (series == label) ++full_rows;
        if (in_csv.number(k, "theta_i_deg") != 45.0) continue;
        (series == label ? full_y : fast_y)[in_csv.number(k, "view_deg")] = in_csv.number(k, "Y");
    }
    QCOMPARE(full_rows, std::size_t{5 * 69});
    std::size_t ab_full_rows = 0;
    for (const QStringList& row : ab_csv.rows)
        if (row[0] == label) ++ab_full_rows;
    QCOMPARE(ab_full_rows, std::size_t{6});
    // Loose factor 3 per point: the full model (explicit flakes) and the fast
    // model's continuum approximation of the flakes differ by up to tens of
    // percent for metal flakes, for this silver metallic +39 to +53 % per
    // geometry, up to +180 % near specular for larger ones (docs/VALIDATION.md;
    // here the full model is ~1.5 times the fast one along the 45 degree curve),
    // and a short budget adds Monte Carlo noise on top. It catches a wrong basis,
    // a swapped series or a unit (pi, steradian) error, not the physics.
    // Point by point only up to 70 degrees from the normal: at grazing views a
    // short run leaves a few paths per cell, and one view at -85 degrees read
    // 3.3 times the fast model in a clean-clone CI run; beyond 70 the mean must
    // hold. The worst view up to 70 degrees read 1.6-2.2 times the fast model
    // at 100-190k paths (20 seeds), 2.0-7.7 times at 15-36k (docs/PERFORMANCE.md).
    QCOMPARE(full_y.size(), std::size_t{69});
    double fast_sum = 0.0;
    double full_sum = 0.0;
    double fast_grazing = 0.0;
    double full_grazing = 0.0;
    for (const auto& [view, y] : fast_y) {
        const double full = full_y[view];
        fast_sum += y;
        full_sum += full;
        if (std::abs(view) > 70.0) {
            fast_grazing += y;
            full_grazing += full;
            continue;
        }
        QVERIFY2(
            full > y / 3.0 && full < 3.0 * y,
            qPrintable(QStringLiteral("45 deg, view %1: full Y %2, fast Y %3").arg(view).arg(full).arg(y)));
    }
    QVERIFY2(full_grazing > fast_grazing / 3.0 && full_grazing < 3.0 * fast_grazing,
             qPrintable(QStringLiteral("45 deg, views beyond 70: full Y %1, fast Y %2 (sums)")
                            .arg(full_grazing)
                            .arg(fast_grazing)));
    qInfo("45 deg curve: mean Y full %.4g, fast %.4g (ratio %.2f)", full_sum / 69.0, fast_sum / 69.0,
          full_sum / fast_sum);
    // "Clear comparison" removes it.
    clickButton(*dock, "plots_unpin");
    QVERIFY(!dock->inplanePlot()->hasComparison() && !dock->abChart()->hasComparison() &&
            !dock->paintSpectra()->hasComparison());
    // The status no longer names a comparison that is gone (issue 27 item 10).
    QVERIFY2(!dock->status()->text().contains(QStringLiteral("full model")),
             qPrintable(dock->status()->text()));
    QVERIFY(dock->fullModelLabel().isEmpty());
}

void FullModelOverlayTest::fullModelCancelStopsTheRun() {
    auto dock = silverDock(silverRecipe());
    dock->fullModelSeconds()->setValue(600);
    QSignalSpy ended(dock.get(), &PlotsDock::fullModelEnded);
    clickButton(*dock, "plots_full_model");
    auto* progress = dock->findChild<QWidget*>(QStringLiteral("plots_full_model_progress"));
    QVERIFY(progress != nullptr && progress->isVisible());
    QTest::qWait(2000);  // well into the paths (past the grid and the flake tiles)
    QVERIFY(dock->fullModelRunning());
    // The grid's fast model alone is 2 % of the progress.
    auto* bar = dock->findChild<QProgressBar*>(QStringLiteral("plots_full_model_progress"));
    QVERIFY(bar != nullptr);
    QVERIFY2(bar->value() >= 1, qPrintable(QString::number(bar->value())));
    QElapsedTimer timer;
    timer.start();
    clickButton(*dock, "plots_full_model_cancel");
    // Stopped by the cancel, not by the 600 s budget: 30 s leaves room for a
    // loaded CI machine. How fast it stops is a measurement (logged), not a
    // pass condition.
    QTRY_VERIFY_WITH_TIMEOUT(!dock->fullModelRunning(), 30000);
    const qint64 ms = timer.elapsed();
    qInfo("full model cancelled after %lld ms", static_cast<long long>(ms));
    QCOMPARE(ended.count(), 1);
    QCOMPARE(ended.at(0).at(0).toBool(), false);
    QVERIFY(!progress->isVisible());
    QTest::qWait(200);
    QVERIFY(!dock->inplanePlot()->hasComparison() && !dock->abChart()->hasComparison());
}

void FullModelOverlayTest::fullModelNewestRequestWins() {
    // A long run, then a short one: the first is cancelled and delivers
    // nothing (no cancelled() for it either), the second is the overlay.
    auto dock = silverDock(silverRecipe());
    QSignalSpy ended(dock.get(), &PlotsDock::fullModelEnded);
    dock->fullModelSeconds()->setValue(600);
    dock->compareWithFullModel();
    QTest::qWait(300);
    dock->fullModelSeconds()->setValue(1);
    dock->compareWithFullModel();
    QTRY_VERIFY_WITH_TIMEOUT(ended.count() == 1 && !dock->fullModelRunning(), kWaitMs);
    QCOMPARE(ended.at(0).at(0).toBool(), true);
    QTRY_VERIFY_WITH_TIMEOUT(dock->inplanePlot()->hasComparison() && !dock->computing(), kWaitMs);
    QVERIFY2(dock->fullModelLabel().startsWith(QStringLiteral("full model (Monte Carlo, ")) &&
                 !dock->fullModelLabel().contains(QStringLiteral("recipe as at")),
             qPrintable(dock->fullModelLabel()));
    QTest::qWait(200);
    QCOMPARE(ended.count(), 1);
}

void FullModelOverlayTest::fullModelErrorNamesTheField() {
    // The full model needs every layer thicker than 0 (runMonteCarlo); the fast model does not.
    Recipe recipe = silverRecipe();
    recipe.layers[0].thickness_um = 0.0;
    auto dock = silverDock(recipe);
    QSignalSpy ended(dock.get(), &PlotsDock::fullModelEnded);
    dock->compareWithFullModel();
    QTRY_VERIFY_WITH_TIMEOUT(ended.count() == 1, kWaitMs);
    QCOMPARE(ended.at(0).at(0).toBool(), false);
    auto* box = dock->findChild<QMessageBox*>(QStringLiteral("error_dialog"));
    QVERIFY(box != nullptr);
    qInfo("full model error: %s", qPrintable(box->text()));
    QVERIFY2(box->text().contains(QStringLiteral("thickness")), qPrintable(box->text()));
    QVERIFY(!dock->inplanePlot()->hasComparison());
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<FullModelOverlayTest>(argc, argv, "PaintLab-test-full-model-overlay");
}

#include "test_full_model_overlay.moc"
