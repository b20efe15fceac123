// The GUI's file dialogs with the plugin registry's formats (issue 29, part
// 1; gui/src/format_dialog.h), driven through the dialogs themselves (Qt's
// own, answered by object name): the filters list every format the loaded
// plugins offer (MERL and the multi-angle CGATS come from plugin libraries;
// the GUI's code names no format), a MERL file chosen in File > Import into
// database is stored as a BRDF measurement, a truncated one is refused with
// a message naming it and nothing stored, and File > Export appearance
// writes through the exporter the chosen filter names. No scene; seconds.

#include "author_setting.h"
#include "database_worker.h"
#include "gui_test_main.h"
#include "main_window.h"
#include "match_dock.h"
#include "modal_answers.h"
#include "workstation_fixture.h"

#include "paintlab/database/database.h"
#include "paintlab/database/measurements.h"
#include "paintlab/plugins/exchange.h"

#include <QAction>
#include <QComboBox>
#include <QFileDialog>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <memory>
#include <vector>

using paintlab::gui::MainWindow;
using paintlab::test::kGuiWaitMs;
using paintlab::test::ModalAnswers;
namespace db = paintlab::db;
namespace plugins = paintlab::plugins;

namespace {

const QString kSolidRed = QStringLiteral("Solid red (iron oxide)");

// A MERL BRDF binary (plugins/merl/merl_format.h): dimensions 90, 90, 180,
// then the R, G and B planes of doubles; a constant raw value is a
// Lambertian surface. `bytes` > 0 keeps only the first bytes (a truncated copy).
void writeMerl(const QString& path, std::size_t bytes = 0) {
    const std::int32_t dims[3] = {90, 90, 180};
    const std::vector<double> plane(std::size_t{90} * 90 * 180, 150.0);
    std::string data(reinterpret_cast<const char*>(dims), sizeof(dims));
    for (int channel = 0; channel < 3; ++channel)
        data.append(reinterpret_cast<const char*>(plane.data()), plane.size() * sizeof(double));
    if (bytes > 0) data.resize(bytes);
    std::ofstream(path.toStdString(), std::ios::binary) << data;
}

// The filter of a dialog that names the format with this extension (not "All supported").
QString filterFor(const QStringList& filters, const QString& pattern) {
    for (const QString& filter : filters)
        if (!filter.startsWith(QFileDialog::tr("All supported")) && filter.contains(pattern)) return filter;
    return {};
}

// Answers a file dialog: the filter naming `pattern` (empty: "All supported"), the file, Open/Save.
ModalAnswers::Answer choose(const QString& file, const QString& pattern = {}) {
    return [file, pattern](QWidget* w) {
        auto* dialog = qobject_cast<QFileDialog*>(w);
        if (!pattern.isEmpty()) dialog->selectNameFilter(filterFor(dialog->nameFilters(), pattern));
        // Typed into the name field, as a user does (selectFile leaves a focused field as it is).
        auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
        if (name != nullptr) name->setText(file);
        dialog->selectFile(file);
        static_cast<QDialog*>(dialog)->accept();  // QFileDialog's own accept(): as the Open/Save button
    };
}

ModalAnswers::Answer readFilters(QStringList* filters) {
    return [filters](QWidget* w) {
        auto* dialog = qobject_cast<QFileDialog*>(w);
        *filters = dialog->nameFilters();
        dialog->reject();
    };
}

ModalAnswers::Answer readMessage(QString* text) {
    return [text](QWidget* w) {
        auto* box = qobject_cast<QMessageBox*>(w);
        *text = box->text();
        box->button(QMessageBox::Ok)->click();
    };
}

// Every format of these kinds has its filter: "description (*.ext ...)".
void expectEveryFormat(const QStringList& filters, const std::vector<plugins::OfferKind>& kinds) {
    for (const auto kind : kinds)
        for (const auto& format : plugins::offeredFormats(plugins::Registry::global(), kind)) {
            const QString description = QString::fromStdString(format.description);
            bool found = false;
            for (const QString& filter : filters)
                found = found || filter.startsWith(description + " (*" +
                                                   QString::fromStdString(format.extensions.front()));
            QVERIFY2(found, qPrintable(description));
        }
}

}  // namespace

class FileFormatsTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void filtersListThePluginFormats();
    void aMerlFileChosenInTheImportDialogIsStored();
    void aTruncatedFileIsRefusedAndNothingStored();
    void exportAppearanceWritesTheChosenFormat();
    void cleanupTestCase();

private:
    QAction* action(const char* name) { return m_window->findChild<QAction*>(name); }
    std::size_t storedMeasurements();

    QTemporaryDir m_dir;
    QString m_db_file;
    std::unique_ptr<MainWindow> m_window;
};

void FileFormatsTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    QCoreApplication::setAttribute(Qt::AA_DontUseNativeDialogs);  // Qt's own dialog: the test answers it
    m_db_file = m_dir.path() + "/lab.db";
    m_window = paintlab::test::openWorkstation(paintlab::test::withoutScene(m_db_file));
    QVERIFY(m_window != nullptr);
    QVERIFY(m_window->selectRecipe(kSolidRed));
}

void FileFormatsTest::cleanupTestCase() { m_window.reset(); }

std::size_t FileFormatsTest::storedMeasurements() {
    db::Database database = db::Database::open(m_db_file.toStdString());
    return db::listMeasurements(database).size();
}

void FileFormatsTest::filtersListThePluginFormats() {
    // The MERL and multi-angle formats come from plugin libraries of the build
    // tree: without them loaded this test would prove nothing.
    const plugins::Registry& registry = plugins::Registry::global();
    bool merl = false;
    bool multiangle = false;
    for (const auto& loaded : registry.plugins()) {
        merl = merl || loaded.name == "merl";
        multiangle = multiangle || loaded.name == "multiangle";
    }
    QVERIFY2(merl && multiangle, "the merl and multiangle plugins are loaded from the build tree");

    ModalAnswers answers;
    QStringList match_filters;
    QStringList import_filters;
    QStringList export_filters;
    answers.expect("match_import_dialog", readFilters(&match_filters));
    answers.expect("database_import_dialog", readFilters(&import_filters));
    answers.expect("appearance_export_dialog", readFilters(&export_filters));
    m_window->matchDock()->findChild<QPushButton*>("match_import")->click();
    action("import_action")->trigger();
    action("export_appearance_action")->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(answers.done(), kGuiWaitMs);
    QVERIFY2(answers.unexpected().isEmpty(), qPrintable(answers.unexpected().join(", ")));

    // "All supported" first, with the plugins' extensions; every format; "All files" last.
    for (const QStringList* filters : {&match_filters, &import_filters}) {
        QVERIFY(filters->size() >= 3);
        QVERIFY(filters->front().startsWith(QFileDialog::tr("All supported (")));
        QVERIFY(filters->front().contains("*.binary"));
        QVERIFY(filters->front().contains("*.cgats"));
        QCOMPARE(filters->back(), QFileDialog::tr("All files (*)"));
    }
    expectEveryFormat(match_filters, {plugins::OfferKind::MeasurementImport});
    QVERIFY(filterFor(match_filters, "*.binary").startsWith("MERL BRDF binary"));
    QVERIFY(filterFor(match_filters, "*.cgats").contains("multi-angle"));
    expectEveryFormat(import_filters,
                      {plugins::OfferKind::MeasurementImport, plugins::OfferKind::SpectraImport,
                       plugins::OfferKind::IngredientImport});
    // Saving: "All supported", then every AppearanceExporter (the BRDF table, MERL, and any plugin's).
    QVERIFY(export_filters.front().startsWith(QFileDialog::tr("All supported (")));
    expectEveryFormat(export_filters, {plugins::OfferKind::AppearanceExport});
    QVERIFY(!filterFor(export_filters, "*.binary").isEmpty());
    QCOMPARE(static_cast<std::size_t>(export_filters.size()),
             1 + plugins::offeredFormats(registry, plugins::OfferKind::AppearanceExport).size());
}

void FileFormatsTest::aMerlFileChosenInTheImportDialogIsStored() {
    const QString file = m_dir.filePath("gonio-panel.binary");
    writeMerl(file);
    const std::size_t before = storedMeasurements();
    QSignalSpy imported(m_window.get(), &MainWindow::importFinished);
    ModalAnswers answers;
    answers.expect("database_import_dialog", choose(file, "*.binary"));  // the MERL filter: its format id
    action("import_action")->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(imported.count() == 1, kGuiWaitMs);
    QVERIFY2(imported.front().at(0).toBool(), qPrintable(imported.front().at(1).toString()));
    QVERIFY(answers.unexpected().isEmpty());

    db::Database database = db::Database::open(m_db_file.toStdString());
    const auto stored = db::findMeasurement(database, "gonio-panel");
    QVERIFY(stored.has_value());
    QCOMPARE(stored->kind, db::MeasurementKind::Brdf);
    // Subsampled to the importer's default (4096 bins, plugins/README.md), RGB.
    QVERIFY(!stored->samples.empty() && stored->samples.size() <= 4096);
    QCOMPARE(stored->channels.size(), std::size_t{3});
    QCOMPARE(storedMeasurements(), before + 1);
    // The Match dock lists it at once.
    QVERIFY(m_window->matchDock()->measurementBox()->findText("gonio-panel", Qt::MatchStartsWith) >= 0);
}

void FileFormatsTest::aTruncatedFileIsRefusedAndNothingStored() {
    const QString file = m_dir.filePath("cut-short.binary");
    writeMerl(file, 100000);
    const std::size_t before = storedMeasurements();
    QSignalSpy imported(m_window.get(), &MainWindow::importFinished);
    ModalAnswers answers;
    QString shown;
    answers.expect("database_import_dialog", choose(file));  // "All supported": chosen by extension
    answers.expect("error_dialog", readMessage(&shown));
    action("import_action")->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(imported.count() == 1 && answers.done(), kGuiWaitMs);
    QVERIFY(!imported.front().at(0).toBool());
    const QString message = imported.front().at(1).toString();
    QVERIFY2(message.contains(file) && message.contains("truncated"), qPrintable(message));
    QVERIFY2(shown.contains(file) && shown.contains("Nothing of the file was stored"), qPrintable(shown));
    QCOMPARE(storedMeasurements(), before);

    // The Match dock's File... reads it through the same registry: refused, said in the dock.
    QVERIFY(!m_window->matchDock()->readFile(file));
    QVERIFY(m_window->matchDock()->status()->text().contains("cut-short.binary"));
}

void FileFormatsTest::exportAppearanceWritesTheChosenFormat() {
    // The BRDF table's JSON filter, the name typed without an extension: it gets the format's.
    const QString typed = m_dir.filePath("solid-red-brdf");
    QSignalSpy exported(m_window.get(), &MainWindow::appearanceExported);
    ModalAnswers answers;
    answers.expect("appearance_export_dialog", choose(typed, "*.json"));
    action("export_appearance_action")->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(exported.count() == 1, kGuiWaitMs);
    QVERIFY2(exported.front().at(0).toBool(), qPrintable(exported.front().at(1).toString()));
    std::ifstream in((typed + ".json").toStdString());
    const auto table = nlohmann::json::parse(in);
    QCOMPARE(table.at("settings").at("preset").get<std::string>(), std::string("standard"));
    QVERIFY(!table.at("wavelengths_nm").empty());

    // glTF writes a painted object: the workstation asks which, and the file holds it.
    const QString gltf = m_dir.filePath("solid-red-panel.gltf");
    answers.expect("appearance_export_dialog", choose(gltf));
    QString offered;
    answers.expect("export_object_dialog", [&offered](QWidget* w) {
        auto* dialog = qobject_cast<QInputDialog*>(w);
        offered = dialog->comboBoxItems().join(',');
        dialog->setTextValue(QStringLiteral("panel"));
        dialog->accept();
    });
    action("export_appearance_action")->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(exported.count() == 2, kGuiWaitMs);
    QVERIFY2(exported.back().at(0).toBool(), qPrintable(exported.back().at(1).toString()));
    QCOMPARE(offered, QStringLiteral("sphere,panel,car"));
    // The status names the approximation's colour error (the exporter's report).
    QVERIFY2(exported.back().at(1).toString().contains(QStringLiteral("ΔE00")),
             qPrintable(exported.back().at(1).toString()));
    std::ifstream gltf_in(gltf.toStdString());
    const auto asset = nlohmann::json::parse(gltf_in);
    QVERIFY2(asset.dump().find("\"panel\"") != std::string::npos, "the painted object is not the panel");

    // A file no exporter claims: refused before any work, the formats listed.
    QString shown;
    answers.expect("error_dialog", readMessage(&shown));
    QVERIFY(!m_window->exportAppearance(m_dir.filePath("paint.xyz")));
    QTRY_VERIFY_WITH_TIMEOUT(answers.done(), kGuiWaitMs);
    QVERIFY(answers.unexpected().isEmpty());
    QVERIFY2(shown.contains(".xyz") && shown.contains("merl-binary"), qPrintable(shown));
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<FileFormatsTest>(argc, argv, "paintlab-file-formats-test");
}

#include "test_file_formats.moc"
