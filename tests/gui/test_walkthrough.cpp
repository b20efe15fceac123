// A technician's day with the workstation, screen by screen (issue 27, the
// walkthrough): the first start's hint, picking a recipe in the list, typing
// a thickness, Ctrl+Z from the field, adding an ingredient, saving a version
// (the note asked in a modal dialog, answered by modal_answers.h), comparing
// with the first version in the render, the production sheet, the plots, the
// accuracy verdict, and "-5" typed into a field. Each step is driven through
// the widgets a person uses (list, field and keys, shortcuts, dock buttons),
// checks what the step must change, and compares the window (or the dialog)
// with its baseline in tests/gui/baselines/walk-*.png (screenshot_baseline.h),
// so that the next change that breaks a step of the day fails CI.
//
// The main window at 1366 x 768 on a demo database and the tiny demo scene
// (workstation_fixture.h); the measured times and the temporary folder's path
// are masked before each screenshot (the saved version's time and checksum
// in the production dialog are not: a few characters, SSIM 0.989 against a
// baseline of another run). About 12 s on a loaded 2-core machine.

#include "gui_test_main.h"
#include "modal_answers.h"
#include "screenshot_baseline.h"
#include "workstation_fixture.h"

#include "accuracy_dock.h"
#include "author_setting.h"
#include "ingredient_dock.h"
#include "main_window.h"
#include "plots_dock.h"
#include "production_dialog.h"
#include "recipe_editor_dock.h"
#include "render_dock.h"
#include "versions_dock.h"

#include "paintlab/database/database.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/recipe.h"

#include <QDoubleSpinBox>
#include <QFile>
#include <QLabel>
#include <QListWidget>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include <memory>

using paintlab::gui::MainWindow;
using paintlab::test::kGuiWaitMs;
using paintlab::test::ModalAnswers;

namespace {

const QString kPearl = QStringLiteral("Blue pearl over black (two layers)");
const QString kRutile = QStringLiteral("titanium dioxide white (rutile)");

}  // namespace

class WalkthroughTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void step01StartSaysWhatToDo();
    void step02PickARecipe();
    void step03TypeAThickness();
    void step04UndoFromTheField();
    void step05AddAnIngredient();
    void step06SaveAVersion();
    void step07CompareWithTheFirstVersion();
    void step08ProductionSheet();
    void step09Plots();
    void step10Accuracy();
    void step11BadInputIsRefusedVisibly();
    void cleanupTestCase();

private:
    void waitIdle();
    // Waits for the renders and plots, masks what changes from run to run,
    // and compares `widget` with the baseline walk-<name>.
    void screenshot(QWidget& widget, const QString& name);
    // Layer 0: the clear coat, 1: the basecoat.
    QDoubleSpinBox* thicknessField(int layer) const;
    double thickness(int layer) const {
        return m_window->document()->recipe().layers.at(static_cast<std::size_t>(layer)).thickness_um;
    }
    void typeInto(QDoubleSpinBox* field, const QString& text);
    QTemporaryDir m_dir;
    std::unique_ptr<MainWindow> m_window;
};

void WalkthroughTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    paintlab::gui::WorkstationOptions options;
    options.database = (m_dir.path() + "/lab.db").toStdString();
    options.scene = paintlab::test::writeTinyDemoScene(m_dir.path()).toStdString();
    options.raymap_follows_view = false;  // the tiny scene as it is
    options.refine_ray_map = false;       // screenshots of one fixed map, not of a map refining meanwhile
    m_window = paintlab::test::openWorkstation(options, QSize(1366, 768));
    QVERIFY(m_window != nullptr);
    QTRY_VERIFY_WITH_TIMEOUT(m_window->scheduler()->rayMap() != nullptr, kGuiWaitMs);
}

void WalkthroughTest::cleanupTestCase() { m_window.reset(); }

void WalkthroughTest::waitIdle() {
    QTRY_VERIFY_WITH_TIMEOUT(m_window->scheduler()->idle() && m_window->comparisonScheduler()->idle() &&
                                 !m_window->plotsDock()->computing(),
                             kGuiWaitMs);
}

void WalkthroughTest::screenshot(QWidget& widget, const QString& name) {
    waitIdle();
    QTest::qWait(200);  // the last repaints of the plots and docks
    paintlab::test::maskMeasuredTimes(*m_window);
    paintlab::test::maskMeasuredTimes(widget);
    for (QLabel* label : widget.findChildren<QLabel*>())  // a file written, a status line
        if (label->text().contains(m_dir.path()))
            label->setText(label->text().replace(m_dir.path(), QStringLiteral("<folder>")));
    const QString status = m_window->statusBar()->currentMessage();
    if (status.contains(m_dir.path()))
        m_window->statusBar()->showMessage(QString(status).replace(m_dir.path(), QStringLiteral("<folder>")));
    // Threshold: mean SSIM 0.98, as the workstation's baselines
    // (test_workstation.cpp: renders and layout deterministic, times masked;
    // a blank plot there gives 0.962).
    const auto result = paintlab::test::compareWithBaseline(widget, QStringLiteral("walk-") + name, 0.98);
    qInfo("%s", qPrintable(result.message));
    QVERIFY2(result.ok, qPrintable(result.message));
}

QDoubleSpinBox* WalkthroughTest::thicknessField(int layer) const {
    // The thickness rows in layer order.
    const auto fields = m_window->editorDock()->findChildren<QDoubleSpinBox*>(QStringLiteral("thickness_um"));
    return layer < fields.size() ? fields[layer] : nullptr;
}

void WalkthroughTest::typeInto(QDoubleSpinBox* field, const QString& text) {
    QVERIFY(field != nullptr);
    m_window->activateWindow();
    field->setFocus();
    field->selectAll();
    QTest::keyClicks(field, text);
    QTest::keyClick(field, Qt::Key_Return);
}

void WalkthroughTest::step01StartSaysWhatToDo() {
    QVERIFY(!m_window->document()->hasRecipe());
    QVERIFY2(m_window->statusBar()->currentMessage().contains(QStringLiteral("pick a recipe")),
             qPrintable(m_window->statusBar()->currentMessage()));
    screenshot(*m_window, QStringLiteral("01-start"));
}

void WalkthroughTest::step02PickARecipe() {
    const auto found = m_window->recipeList()->findItems(kPearl, Qt::MatchStartsWith);
    QVERIFY(!found.isEmpty());
    m_window->recipeList()->setCurrentItem(found.front());  // a click's selection
    QTRY_VERIFY_WITH_TIMEOUT(m_window->document()->hasRecipe(), kGuiWaitMs);
    QCOMPARE(QString::fromStdString(m_window->document()->recipe().name), kPearl);
    QTRY_VERIFY_WITH_TIMEOUT(!m_window->renderDock()->image().isNull(), kGuiWaitMs);
    QVERIFY(m_window->windowTitle().contains(QStringLiteral("version 1")));
    screenshot(*m_window, QStringLiteral("02-recipe"));
}

void WalkthroughTest::step03TypeAThickness() {
    // The basecoat's (the clear coat's lacquer does not absorb: its thickness leaves the colour).
    QCOMPARE(thickness(1), 15.0);
    const QImage before = m_window->renderDock()->image();
    QSignalSpy rendered(m_window->scheduler(), &paintlab::gui::RenderScheduler::finished);
    typeInto(thicknessField(1), QStringLiteral("30"));
    QCOMPARE(thickness(1), 30.0);
    QTRY_VERIFY_WITH_TIMEOUT(!rendered.isEmpty(), kGuiWaitMs);
    waitIdle();
    QVERIFY(m_window->renderDock()->image() != before);
    QVERIFY(m_window->windowTitle().contains(QStringLiteral("modified since version 1")));
    screenshot(*m_window, QStringLiteral("03-thickness"));
}

void WalkthroughTest::step04UndoFromTheField() {
    QDoubleSpinBox* field = thicknessField(1);
    QVERIFY(field != nullptr && field->hasFocus());
    QTest::keyClick(field, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(thickness(1), 15.0);
    QCOMPARE(thicknessField(1)->text(), QStringLiteral("15 µm"));
    QVERIFY(m_window->document()->undoStack()->isClean());
    screenshot(*m_window, QStringLiteral("04-undo"));
}

void WalkthroughTest::step05AddAnIngredient() {
    paintlab::gui::IngredientDock* ingredients = m_window->ingredientDock();
    ingredients->raise();
    const std::size_t components = m_window->document()->recipe().layers.at(1).components.size();
    QVERIFY(ingredients->selectIngredient(paintlab::db::IngredientKind::Pigment, kRutile));
    QVERIFY(ingredients->addToLayer(1));  // the basecoat
    const paintlab::Recipe& recipe = m_window->document()->recipe();
    QCOMPARE(recipe.layers.at(1).components.size(), components + 1);
    QCOMPARE(paintlab::componentName(recipe.layers[1].components.back()), kRutile.toStdString());
    screenshot(*m_window, QStringLiteral("05-ingredient"));
    m_window->editorDock()->raise();
}

void WalkthroughTest::step06SaveAVersion() {
    ModalAnswers answers;
    answers.expect(QStringLiteral("version_note_dialog"), ModalAnswers::type(QStringLiteral("rutile added")));
    QTest::keyClick(m_window.get(), Qt::Key_S, Qt::ControlModifier);  // File > Save version...
    QTRY_VERIFY_WITH_TIMEOUT(answers.done(), kGuiWaitMs);
    QVERIFY2(answers.unexpected().isEmpty(), qPrintable(answers.unexpected().join(", ")));
    auto db = paintlab::db::Database::open((m_dir.path() + "/lab.db").toStdString());
    const auto history = paintlab::db::recipeHistory(db, kPearl.toStdString());
    QCOMPARE(static_cast<int>(history.size()), 2);
    QCOMPARE(QString::fromStdString(history.back().note), QStringLiteral("rutile added"));
    QVERIFY2(m_window->windowTitle().contains(QStringLiteral("version 2")),
             qPrintable(m_window->windowTitle()));
    QVERIFY(m_window->recipeList()->currentItem() != nullptr);
    screenshot(*m_window, QStringLiteral("06-saved"));
}

void WalkthroughTest::step07CompareWithTheFirstVersion() {
    QVERIFY(m_window->versionsDock()->compareInRender(1));
    QTRY_VERIFY_WITH_TIMEOUT(!m_window->renderDock()->comparisonImage().isNull(), kGuiWaitMs);
    QVERIFY(m_window->renderDock()->mode() == paintlab::gui::CompareMode::SideBySide);
    QVERIFY(m_window->renderDock()->comparisonImage() != m_window->renderDock()->image());
    screenshot(*m_window, QStringLiteral("07-compare"));
    m_window->clearComparison();
}

void WalkthroughTest::step08ProductionSheet() {
    paintlab::gui::ProductionDialog* dialog = m_window->openProductionDialog();
    QVERIFY(dialog != nullptr && dialog->isVisible());
    QCOMPARE(dialog->recipeName(), kPearl);
    QCOMPARE(dialog->version().value_or(0), 2);  // the version just saved
    const QString file = m_dir.path() + "/pearl-v2.csv";
    dialog->setOutputFile(file);
    QSignalSpy exported(dialog, &paintlab::gui::ProductionDialog::exported);
    QVERIFY(dialog->exportSheet());
    QTRY_COMPARE_WITH_TIMEOUT(exported.count(), 1, kGuiWaitMs);
    QVERIFY2(QFile::exists(exported.at(0).at(0).toString()), qPrintable(exported.at(0).at(0).toString()));
    // The dialog's file field holds the temporary folder: masked for the screenshot.
    dialog->setOutputFile(QStringLiteral("/production/pearl-v2.csv"));
    screenshot(*dialog, QStringLiteral("08-production"));
    dialog->close();
}

void WalkthroughTest::step09Plots() {
    m_window->plotsDock()->raise();
    auto* tabs = m_window->plotsDock()->findChild<QTabWidget*>(QStringLiteral("plots_tabs"));
    QVERIFY(tabs != nullptr);
    for (int i = 0; i < tabs->count(); ++i) {
        tabs->setCurrentIndex(i);
        const QString name = tabs->tabText(i).toLower().remove(QRegularExpression(QStringLiteral("[^a-z]")));
        screenshot(*m_window, QStringLiteral("09-plots-") + name);
    }
    tabs->setCurrentIndex(0);
}

void WalkthroughTest::step10Accuracy() {
    m_window->accuracyDock()->raise();
    auto* verdict = m_window->accuracyDock()->findChild<QLabel*>(QStringLiteral("accuracy_verdict"));
    QVERIFY(verdict != nullptr);
    QTRY_VERIFY_WITH_TIMEOUT(!verdict->text().isEmpty(), kGuiWaitMs);
    screenshot(*m_window, QStringLiteral("10-accuracy"));
    m_window->plotsDock()->raise();
}

void WalkthroughTest::step11BadInputIsRefusedVisibly() {
    QLabel* said = m_window->editorDock()->messageFor("thickness_um");
    QVERIFY(said != nullptr);
    typeInto(thicknessField(0), QStringLiteral("-5"));
    QCOMPARE(thickness(0), 40.0);  // nothing applied
    QVERIFY2(!said->isHidden() && said->text().contains(QStringLiteral("kept 40 µm")),
             qPrintable(said->text()));
    QVERIFY(m_window->document()->undoStack()->isClean());
    screenshot(*m_window, QStringLiteral("11-bad-input"));
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<WalkthroughTest>(argc, argv, "PaintLab-test-walkthrough");
}

#include "test_walkthrough.moc"
