// The workstation's database docks under a virtual X server (registered as
// gui.docks in tests/gui/CMakeLists.txt, run in xvfb-run like gui.workstation):
// the ingredient browser's search and kind filter, its validated editing,
// import and export, adding an ingredient to a layer; the recipe versions'
// diff and revert; the production export dialog; dock layout and recent
// files kept across a restart. No scene is opened (the docks need none).
//
// Every dialog is non-modal (open(), never exec()), so nothing here waits on
// a nested event loop; the message boxes a test provokes are checked and
// deleted. Each dock is saved as a PNG under the build folder
// (PAINTLAB_SCREENSHOT_DIR) for the screenshot comparison; no baseline here.

#include "author_setting.h"
#include "gui_test_main.h"
#include "ingredient_dock.h"
#include "main_window.h"
#include "production_dialog.h"
#include "recipe_diff.h"
#include "recipe_editor_dock.h"
#include "save_screenshot.h"
#include "spectrum_chart.h"
#include "versions_dock.h"
#include "workstation_fixture.h"

#include "paintlab/database/database.h"
#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"

#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QLineEdit>
#include <QMessageBox>
#include <QSettings>
#include <QSignalSpy>
#include <QSlider>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeView>
#include <QUndoStack>
#include <QWheelEvent>

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <sstream>

using paintlab::gui::IngredientDock;
using paintlab::gui::MainWindow;
namespace db = paintlab::db;

namespace {

constexpr int kWaitMs = 60000;  // ASan on a loaded CI machine
const QString kPearl = QStringLiteral("Blue pearl over black (two layers)");
const QString kRutile = QStringLiteral("titanium dioxide white (rutile)");

std::string readText(const QString& path) {
    std::ifstream in(path.toStdString(), std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

using paintlab::test::saveScreenshot;

}  // namespace

class DocksTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void searchAndKindFilterNarrowTheIngredientList();
    void selectedIngredientShowsFieldsSourcesAndSpectra();
    void invalidEditIsRefusedNamingTheFieldAndNothingIsSaved();
    void validEditIsSaved();
    void exportThenImportIngredients();
    void badImportNamesTheFileAndRecordAndStoresNothing();
    void addingAnIngredientToALayerIsUndoable();
    void wheelOverAnUnfocusedFieldLeavesItsValue();
    void diffOfTwoVersionsListsTheChangedParameter();
    void revertCreatesANewVersionEqualToTheOld();
    void diffMatchesComponentsByNameAndSummarisesSpectra();
    void productionExportWritesAFileNamingVersionAndChecksum();
    void productionExportToABadFolderNamesTheFile();
    void dockLayoutAndRecentFilesPersist();
    void cleanupTestCase();

private:
    IngredientDock* ingredients() { return m_window->ingredientDock(); }
    paintlab::gui::VersionsDock* versions() { return m_window->versionsDock(); }
    int listed() { return static_cast<int>(ingredients()->listedIngredients().size()); }
    QString listedName(int row) { return ingredients()->list()->model()->index(row, 0).data().toString(); }
    QString listedKind(int row) { return ingredients()->list()->model()->index(row, 1).data().toString(); }
    void setKind(const QString& label);
    void setSearch(const QString& text);
    void waitListed();
    // The message box of that object name under parent (nullptr if none), its text in *text, then deleted.
    bool takeMessage(QObject* parent, const QString& name, QString* text);
    db::Database openDb() { return db::Database::open(m_db_file.toStdString()); }

    QTemporaryDir m_dir;
    QString m_db_file;
    std::unique_ptr<MainWindow> m_window;
};

void DocksTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    m_db_file = m_dir.path() + "/lab.db";
    m_window = paintlab::test::openWorkstation(paintlab::test::withoutScene(m_db_file));
    QVERIFY(m_window != nullptr);
    waitListed();
}

void DocksTest::setKind(const QString& label) {
    QComboBox* kind = ingredients()->kindFilter();
    const int index = label.isEmpty() ? 0 : kind->findText(label);
    QVERIFY2(index >= 0, qPrintable(label));
    kind->setCurrentIndex(index);
    waitListed();
}

void DocksTest::waitListed() {
    // The search runs on a worker thread after a short pause in the typing.
    QTRY_VERIFY_WITH_TIMEOUT(!ingredients()->searching(), kWaitMs);
}

void DocksTest::setSearch(const QString& text) {
    QLineEdit* search = ingredients()->searchField();
    search->clear();
    QTest::keyClicks(search, text);  // as typed; the list follows after a short delay
    waitListed();
}

bool DocksTest::takeMessage(QObject* parent, const QString& name, QString* text) {
    auto* box = parent->findChild<QMessageBox*>(name);
    if (box == nullptr) return false;
    if (text != nullptr) *text = box->text();
    delete box;
    return true;
}

void DocksTest::searchAndKindFilterNarrowTheIngredientList() {
    const int all = listed();
    QCOMPARE(all, 16);  // packaging/demo/ingredients/demo-ingredients.json
    setSearch(QStringLiteral("flake"));
    QVERIFY(listed() > 0 && listed() < all);
    for (int i = 0; i < listed(); ++i) QVERIFY(listedName(i).contains("flake", Qt::CaseInsensitive));
    setSearch({});
    QCOMPARE(listed(), all);
    setKind(QStringLiteral("pigment"));
    QCOMPARE(listed(), 3);
    for (int i = 0; i < listed(); ++i) QCOMPARE(listedKind(i), "pigment");
    setSearch(QStringLiteral("BLACK"));  // case-insensitive
    QCOMPARE(listed(), 1);
    QCOMPARE(listedName(0), "carbon black");
    setSearch({});
    setKind({});
    QCOMPARE(listed(), all);
}

void DocksTest::selectedIngredientShowsFieldsSourcesAndSpectra() {
    QVERIFY(ingredients()->selectIngredient(db::IngredientKind::Pigment, kRutile));
    QVERIFY(ingredients()->current().has_value());
    auto* density = qobject_cast<QLineEdit*>(ingredients()->fieldEditor("density_g_cm3"));
    QVERIFY(density != nullptr);
    QCOMPARE(density->text(), "4.23");
    QVERIFY(ingredients()->fieldEditor("source") != nullptr);
    QVERIFY(ingredients()->fieldEditor("limits.max_volume_fraction") != nullptr);
    QVERIFY(ingredients()->fieldEditor("hg_g") != nullptr);  // the kind's own scalars
    // Its two spectra with their units and literature sources, the first one drawn.
    QCOMPARE(ingredients()->spectraTable()->rowCount(), 2);
    QCOMPARE(ingredients()->spectraTable()->item(0, 1)->text(), QString::fromUtf8("1/µm"));
    QVERIFY(!ingredients()->spectraTable()->item(0, 3)->text().isEmpty());
    QVERIFY(ingredients()->chart()->hasSpectrum());
    ingredients()->spectraTable()->setCurrentCell(1, 0);
    QCOMPARE(ingredients()->chart()->title(), ingredients()->spectraTable()->item(1, 0)->text());
    ingredients()->raise();
    QCoreApplication::processEvents();
    saveScreenshot(ingredients(), QStringLiteral("dock_ingredients"));
}

void DocksTest::invalidEditIsRefusedNamingTheFieldAndNothingIsSaved() {
    QVERIFY(ingredients()->selectIngredient(db::IngredientKind::Pigment, kRutile));
    auto db_before = openDb();
    const auto found = db::findIngredient(db_before, db::IngredientKind::Pigment, kRutile.toStdString());
    QVERIFY(found.has_value());
    const db::Ingredient before = *found;
    struct Case {
        std::string key;
        QString text;
        QString expect;
    };
    for (const Case& c :
         {Case{"density_g_cm3", "-1", "density_g_cm3"}, Case{"density_g_cm3", "heavy", "not a number"},
          Case{"limits.max_volume_fraction", "2", "limits.max_volume_fraction"}, Case{"hg_g", "1.5", "hg_g"},
          Case{"name", "", "name"}}) {
        QVERIFY(ingredients()->selectIngredient(db::IngredientKind::Pigment, kRutile));
        auto* editor = qobject_cast<QLineEdit*>(ingredients()->fieldEditor(c.key));
        QVERIFY2(editor != nullptr, c.key.c_str());
        editor->setText(c.text);
        QVERIFY(!ingredients()->saveChanges());
        QString message;
        QVERIFY(takeMessage(ingredients(), QStringLiteral("ingredient_error"), &message));
        QVERIFY2(message.contains(c.expect), qPrintable(message));
        if (c.expect != c.key.c_str()) QVERIFY2(message.contains(c.key.c_str()), qPrintable(message));
        // The database holds what it held.
        auto db = openDb();
        const auto stored = db::findIngredient(db, db::IngredientKind::Pigment, kRutile.toStdString());
        QVERIFY(stored.has_value());
        QVERIFY(*stored == before);
        ingredients()->revertChanges();
    }
}

void DocksTest::validEditIsSaved() {
    QVERIFY(ingredients()->selectIngredient(db::IngredientKind::Pigment, kRutile));
    auto* density = qobject_cast<QLineEdit*>(ingredients()->fieldEditor("density_g_cm3"));
    auto* tags = qobject_cast<QLineEdit*>(ingredients()->fieldEditor("tags"));
    QVERIFY(density != nullptr && tags != nullptr);
    density->setText("4.2");
    tags->setText(tags->text() + ", gui test");
    QVERIFY(ingredients()->saveChanges());
    waitListed();
    auto db = openDb();
    const auto stored = db::findIngredient(db, db::IngredientKind::Pigment, kRutile.toStdString());
    QVERIFY(stored.has_value());
    QCOMPARE(*stored->density_g_cm3, 4.2);
    QVERIFY(std::find(stored->tags.begin(), stored->tags.end(), "gui test") != stored->tags.end());
    QCOMPARE(ingredients()->current()->density_g_cm3.value(), 4.2);
}

void DocksTest::exportThenImportIngredients() {
    setKind(QStringLiteral("pigment"));
    QCOMPARE(listed(), 3);
    // Export the listed pigments as JSON and as CSV (on the worker thread).
    for (const QString& name : {QStringLiteral("pigments.json"), QStringLiteral("pigments.csv")}) {
        QSignalSpy done(ingredients(), &IngredientDock::exportFinished);
        ingredients()->exportFile(m_dir.path() + "/" + name);
        QTRY_COMPARE_WITH_TIMEOUT(done.count(), 1, kWaitMs);
        QVERIFY2(done.at(0).at(0).toBool(), qPrintable(done.at(0).at(1).toString()));
    }
    const auto exported =
        db::parseIngredientsJson(readText(m_dir.path() + "/pigments.json"), "pigments.json");
    QCOMPARE(static_cast<int>(exported.size()), 3);
    QVERIFY(readText(m_dir.path() + "/pigments.csv").rfind("kind,name", 0) == 0);

    // The same pigments under new names come back in.
    nlohmann::json file = nlohmann::json::parse(readText(m_dir.path() + "/pigments.json"));
    for (auto& ingredient : file["ingredients"])
        ingredient["name"] = ingredient["name"].get<std::string>() + " (batch 2)";
    const QString renamed = m_dir.path() + "/pigments-batch2.json";
    std::ofstream(renamed.toStdString()) << file.dump(2);
    QSignalSpy imported(ingredients(), &IngredientDock::importFinished);
    ingredients()->importFile(renamed);
    QTRY_COMPARE_WITH_TIMEOUT(imported.count(), 1, kWaitMs);
    QVERIFY2(imported.at(0).at(0).toBool(), qPrintable(imported.at(0).at(1).toString()));
    waitListed();
    QCOMPARE(listed(), 6);
    setKind({});
}

void DocksTest::badImportNamesTheFileAndRecordAndStoresNothing() {
    nlohmann::json file = nlohmann::json::parse(readText(m_dir.path() + "/pigments.json"));
    for (auto& ingredient : file["ingredients"])
        ingredient["name"] = ingredient["name"].get<std::string>() + " (batch 3)";
    file["ingredients"][1]["density_g_cm3"] = "dense";  // a wrong type in the second record
    const QString bad = m_dir.path() + "/bad-pigments.json";
    std::ofstream(bad.toStdString()) << file.dump(2);
    const int before = listed();
    QSignalSpy imported(ingredients(), &IngredientDock::importFinished);
    ingredients()->importFile(bad);
    QTRY_COMPARE_WITH_TIMEOUT(imported.count(), 1, kWaitMs);
    QVERIFY(!imported.at(0).at(0).toBool());
    QString message;
    QVERIFY(takeMessage(ingredients(), QStringLiteral("ingredient_error"), &message));
    QVERIFY2(message.contains("bad-pigments.json"), qPrintable(message));
    QVERIFY2(message.contains("ingredients[1]"), qPrintable(message));
    QVERIFY2(message.contains("density_g_cm3"), qPrintable(message));
    ingredients()->refresh();
    waitListed();
    QCOMPARE(listed(), before);  // the first, good record was not stored either
    auto db = openDb();
    QVERIFY(!db::findIngredient(db, db::IngredientKind::Pigment, "carbon black (batch 3)").has_value());
}

void DocksTest::addingAnIngredientToALayerIsUndoable() {
    QVERIFY(m_window->selectRecipe(kPearl));
    const paintlab::Recipe before = m_window->document()->recipe();
    const std::size_t components = before.layers.at(1).components.size();
    QVERIFY(ingredients()->selectIngredient(db::IngredientKind::Pigment, kRutile));
    QCOMPARE(ingredients()->layerChoice()->count(), 2);
    const auto sliders_before = m_window->editorDock()->findChildren<QSlider*>().size();
    QVERIFY(ingredients()->addToLayer(1));  // the basecoat
    const paintlab::Recipe& after = m_window->document()->recipe();
    QCOMPARE(after.layers.at(1).components.size(), components + 1);
    QCOMPARE(paintlab::componentName(after.layers[1].components.back()), kRutile.toStdString());
    QCOMPARE(paintlab::componentVolumeFraction(after.layers[1].components.back()), 0.01);
    // The editor shows the new component's parameters at once.
    const auto sliders = m_window->editorDock()->findChildren<QSlider*>().size();
    QVERIFY(sliders > sliders_before);
    // Adding it twice is refused with a message.
    QVERIFY(!ingredients()->addToLayer(1));
    QVERIFY(takeMessage(ingredients(), QStringLiteral("ingredient_error"), nullptr));
    m_window->document()->undoStack()->undo();
    QVERIFY(m_window->document()->recipe() == before);
    QTRY_COMPARE_WITH_TIMEOUT(m_window->editorDock()->findChildren<QSlider*>().size(), sliders_before,
                              kWaitMs);
}

// Scrolling the recipe editor with the wheel must not change the fields that
// pass under the pointer (wheel_scrolls_form.h); a focused field still steps.
void DocksTest::wheelOverAnUnfocusedFieldLeavesItsValue() {
    QVERIFY(m_window->selectRecipe(kPearl));
    QSlider* slider = m_window->editorDock()->sliderFor("thickness_um");
    QVERIFY(slider != nullptr);
    auto* field = m_window->editorDock()->findChild<QDoubleSpinBox*>(QStringLiteral("thickness_um"));
    QVERIFY(field != nullptr);
    const paintlab::Recipe before = m_window->document()->recipe();
    const double shown = field->value();
    const int position = slider->value();
    const auto wheel = [](QWidget* target) {
        const QPointF at(target->width() / 2.0, target->height() / 2.0);
        QWheelEvent event(at, target->mapToGlobal(at), QPoint(), QPoint(0, -120), Qt::NoButton,
                          Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(target, &event);
    };
    m_window->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(m_window.get()));
    m_window->editorDock()->setFocus();
    wheel(field);
    wheel(slider);
    QCOMPARE(field->value(), shown);
    QCOMPARE(slider->value(), position);
    QVERIFY(!field->hasFocus() && !slider->hasFocus());  // the wheel gives no focus either
    QVERIFY(m_window->document()->recipe() == before);
    // With focus (a click or Tab) the wheel steps the field as before.
    field->setFocus();
    QTRY_VERIFY_WITH_TIMEOUT(field->hasFocus(), kWaitMs);
    wheel(field);
    QVERIFY(field->value() != shown);
    m_window->editorDock()->setFocus();  // commits the stepped value: one undo step
    QTRY_VERIFY_WITH_TIMEOUT(!(m_window->document()->recipe() == before), kWaitMs);
    m_window->document()->undoStack()->undo();
    QVERIFY(m_window->document()->recipe() == before);
}

void DocksTest::diffOfTwoVersionsListsTheChangedParameter() {
    QVERIFY(m_window->selectRecipe(kPearl));
    QCOMPARE(versions()->recipeName(), kPearl);
    QCOMPARE(static_cast<int>(versions()->history().size()), 1);
    QSlider* slider = m_window->editorDock()->sliderFor("thickness_um");  // the clear coat's
    QVERIFY(slider != nullptr);
    slider->setValue(slider->value() + 50);
    const double thickness = m_window->document()->recipe().layers[0].thickness_um;
    QSignalSpy saved(m_window.get(), &MainWindow::versionSaved);
    versions()->saveNewVersion(QStringLiteral("thicker clear coat (docks test)"));
    QCOMPARE(saved.count(), 1);
    QCOMPARE(static_cast<int>(versions()->history().size()), 2);
    QCOMPARE(QString::fromStdString(versions()->history().back().note),
             QStringLiteral("thicker clear coat (docks test)"));
    QCOMPARE(m_window->document()->version(), 2);
    QVERIFY(m_window->document()->undoStack()->isClean());

    QVERIFY(versions()->diffVersions(1, 2));
    const auto& diff = versions()->lastDiff();
    QCOMPARE(static_cast<int>(diff.size()), 1);
    QCOMPARE(QString::fromStdString(diff[0].path), QStringLiteral("layers[0] 'clear coat'.thickness_um"));
    QCOMPARE(QString::fromStdString(diff[0].old_value).toDouble(), 40.0);
    QCOMPARE(QString::fromStdString(diff[0].new_value).toDouble(), thickness);
    QCOMPARE(versions()->diffTable()->rowCount(), 1);
    QVERIFY(versions()->diffTable()->item(0, 0)->text().contains("thickness_um"));
    qInfo("diff: %s: %s -> %s", diff[0].path.c_str(), diff[0].old_value.c_str(), diff[0].new_value.c_str());
    versions()->raise();
    QCoreApplication::processEvents();
    saveScreenshot(versions(), QStringLiteral("dock_versions"));
}

void DocksTest::revertCreatesANewVersionEqualToTheOld() {
    const std::optional<int> reverted = versions()->revertTo(1);
    QVERIFY(reverted.has_value());
    QCOMPARE(*reverted, 3);
    auto db = openDb();
    const auto v1 = db::loadRecipeVersion(db, kPearl.toStdString(), 1);
    const auto v3 = db::loadRecipeVersion(db, kPearl.toStdString(), 3);
    QVERIFY(v3.recipe == v1.recipe);
    QCOMPARE(v3.info.checksum_sha256, v1.info.checksum_sha256);
    QCOMPARE(QString::fromStdString(v3.info.note), QStringLiteral("Revert to version 1"));
    // Version 2 is untouched, and the editor now edits version 3.
    QVERIFY(db::loadRecipeVersion(db, kPearl.toStdString(), 2).recipe != v1.recipe);
    QCOMPARE(static_cast<int>(versions()->history().size()), 3);
    QVERIFY(m_window->document()->recipe() == v1.recipe);
    QCOMPARE(m_window->document()->version(), 3);
    QVERIFY(versions()->diffVersions(1, 3));
    QVERIFY(versions()->lastDiff().empty());
}

void DocksTest::diffMatchesComponentsByNameAndSummarisesSpectra() {
    auto db = openDb();
    const paintlab::Recipe before = db::loadRecipeVersion(db, kPearl.toStdString(), 1).recipe;
    paintlab::Recipe after = before;
    auto& basecoat = after.layers.at(1);
    QCOMPARE(paintlab::componentName(basecoat.components.at(1)), std::string("carbon black"));
    basecoat.components.erase(basecoat.components.begin());  // the pearl goes, carbon black moves up
    auto& black = std::get<paintlab::Pigment>(basecoat.components.at(0));
    std::vector<double> values = black.sigma_a_per_um.values();
    const double old_value = values[7];  // 450 nm
    values[7] *= 2.0;                    // a change of exactly old_value
    black.sigma_a_per_um = paintlab::Spectrum(black.sigma_a_per_um.wavelengthsNm(), values);
    const auto diff = paintlab::gui::diffRecipes(before, after);
    QCOMPARE(static_cast<int>(diff.size()), 2);
    QCOMPARE(QString::fromStdString(diff[0].path), QStringLiteral("layers[1] 'basecoat'.components[0] 'blue "
                                                                  "interference pearl (TiO2 on mica)'"));
    QCOMPARE(diff[0].new_value, std::string(paintlab::gui::kAbsent));
    // Matched by name: carbon black's own change, at its new position, and nothing else of it.
    QCOMPARE(QString::fromStdString(diff[1].path),
             QStringLiteral("layers[1] 'basecoat'.components[0] 'carbon black'.sigma_a_per_um"));
    QVERIFY2(QString::fromStdString(diff[1].new_value)
                 .contains(QStringLiteral("largest change %1 at 450 nm").arg(old_value)),
             diff[1].new_value.c_str());
}

void DocksTest::productionExportWritesAFileNamingVersionAndChecksum() {
    paintlab::gui::ProductionDialog* dialog = m_window->openProductionDialog();
    QVERIFY(dialog != nullptr && dialog->isVisible() && !dialog->isModal());
    QCOMPARE(dialog->recipeName(), kPearl);
    QCOMPARE(dialog->version().value_or(0), 3);  // the version being edited
    QVERIFY(dialog->setRecipe(kPearl, 2));
    dialog->setBatchKg(2.5);
    auto db = openDb();
    const std::string checksum = db::loadRecipeVersion(db, kPearl.toStdString(), 2).info.checksum_sha256;
    for (const auto format : {db::FileFormat::Csv, db::FileFormat::Json, db::FileFormat::Html}) {
        dialog->setOutputFile(m_dir.path() + "/production/pearl-v2.txt");
        dialog->setFormat(format);  // gives the file its extension
        QDir().mkpath(m_dir.path() + "/production");
        const QString file = dialog->outputFile();
        QSignalSpy exported(dialog, &paintlab::gui::ProductionDialog::exported);
        QVERIFY(dialog->exportSheet());
        QTRY_COMPARE_WITH_TIMEOUT(exported.count(), 1, kWaitMs);
        QCOMPARE(exported.at(0).at(0).toString(), file);
        QVERIFY2(QFile::exists(file), qPrintable(file));
        const std::string text = readText(file);
        QVERIFY2(text.find(checksum) != std::string::npos, qPrintable(file));
        QVERIFY2(text.find(kPearl.toStdString()) != std::string::npos, qPrintable(file));
        if (format == db::FileFormat::Json) {
            const auto sheet = nlohmann::json::parse(text);
            QCOMPARE(sheet["version"].get<int>(), 2);
            QCOMPARE(sheet["checksum_sha256"].get<std::string>(), checksum);
        } else if (format == db::FileFormat::Html) {
            QVERIFY(text.find("v2</title>") != std::string::npos);
        } else {
            QVERIFY(text.find(kPearl.toStdString() + ",2," + checksum) != std::string::npos);
        }
    }
    saveScreenshot(dialog, QStringLiteral("dialog_production"));
}

void DocksTest::productionExportToABadFolderNamesTheFile() {
    paintlab::gui::ProductionDialog* dialog = m_window->openProductionDialog();
    const QString file = m_dir.path() + "/no-such-folder/sheet.csv";
    dialog->setOutputFile(file);
    dialog->setFormat(db::FileFormat::Csv);
    QSignalSpy failed(dialog, &paintlab::gui::ProductionDialog::exportFailed);
    QVERIFY(dialog->exportSheet());
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, kWaitMs);
    QVERIFY2(failed.at(0).at(0).toString().contains("no-such-folder"),
             qPrintable(failed.at(0).at(0).toString()));
    QString message;
    QVERIFY(takeMessage(dialog, QStringLiteral("production_error"), &message));
    QVERIFY(!QFile::exists(file));
    dialog->close();
}

void DocksTest::dockLayoutAndRecentFilesPersist() {
    // A recipe file opened is remembered.
    const QString recipe = m_dir.path() + "/minimal.json";
    QVERIFY(QFile::copy(QStringLiteral(PAINTLAB_TEST_DATA_DIR) + "/valid_minimal.json", recipe));
    QVERIFY(m_window->openRecipeFile(recipe));
    QCOMPARE(QSettings().value("recentFiles").toStringList().value(0), recipe);
    // The layout the user leaves is the one the next start shows.
    versions()->hide();
    ingredients()->setFloating(true);
    m_window->close();
    paintlab::gui::WorkstationOptions options;
    options.database = m_db_file.toStdString();
    options.open_scene = false;
    m_window = std::make_unique<MainWindow>(options);
    m_window->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
    QVERIFY(versions()->isHidden());
    QVERIFY(ingredients()->isFloating());
    waitListed();
    QCOMPARE(listed(), 19);  // the imported pigments are there
    ingredients()->setFloating(false);
    versions()->show();
}

void DocksTest::cleanupTestCase() { m_window.reset(); }

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<DocksTest>(argc, argv, "PaintLab-docks-test");
}

#include "test_docks.moc"
