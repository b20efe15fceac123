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
#include "main_window.h"
#include "match_dock.h"
#include "plots_dock.h"
#include "replace_recipe_command.h"
#include "save_screenshot.h"
#include "spectra_plot.h"

#include "paintlab/database/database.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"

#include <QComboBox>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

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

}  // namespace

class MatchDockTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void aChoiceThatCannotRunSaysWhy();
    void cancelledFitChangesNothing();
    void fitRecoversTheThicknessAndAcceptIsOneUndoableSavedStep();
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
    qputenv("XDG_CACHE_HOME", (m_dir.path() + "/cache").toUtf8());
    qputenv("XDG_CONFIG_HOME", (m_dir.path() + "/config").toUtf8());
    qputenv("XDG_DATA_HOME", (m_dir.path() + "/data").toUtf8());
    paintlab::gui::rememberAuthor(QStringLiteral("GUI test"));
    m_db_file = m_dir.path() + "/lab.db";
    paintlab::gui::WorkstationOptions options;
    options.database = m_db_file.toStdString();
    options.open_scene = false;
    m_window = std::make_unique<MainWindow>(options);
    m_window->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
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

void MatchDockTest::cleanupTestCase() {
    m_window->document()->undoStack()->clear();  // no unsaved-edits question on close
    m_window.reset();
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<MatchDockTest>(argc, argv, "paintlab-match-test");
}

#include "test_match_dock.moc"
