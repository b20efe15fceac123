// The main window's File > Import into database... and Export appearance...
// (main_window.h): files in and out through the plugin registry, with its
// formats in the dialogs (format_dialog.h), the work off the GUI thread.
// Kept apart from main_window.cpp, which calls addExchangeMenuItems() once.

#include "appearance_export.h"
#include "author_setting.h"
#include "database_worker.h"
#include "format_dialog.h"
#include "ingredient_dock.h"
#include "main_window.h"

#include "paintlab/plugins/exchange.h"

#include <QAction>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QProgressDialog>
#include <QStatusBar>

namespace paintlab::gui {

namespace {

// What an import added, in a line.
QString importedText(const db::ImportResult& result, const QString& path) {
    const auto count = static_cast<int>(result.names.size());
    const QString first = result.names.empty() ? QString() : QString::fromStdString(result.names.front());
    switch (result.kind) {
    case db::ContentKind::Measurement:
        return MainWindow::tr("Imported measurement '%1' from %2").arg(first, path);
    case db::ContentKind::Recipe:
        return MainWindow::tr("Imported recipe '%1' (version %2) from %3")
            .arg(first)
            .arg(result.recipe_version)
            .arg(path);
    case db::ContentKind::Spectra:
        return MainWindow::tr("Imported %n spectra from %1", nullptr, count).arg(path);
    case db::ContentKind::Ingredients:
        break;
    }
    return MainWindow::tr("Imported %n ingredient(s) from %1", nullptr, count).arg(path);
}

// Every importer's format: measurements, spectra and ingredients compete for a file.
std::vector<plugins::FormatInfo> importFormats() {
    const plugins::Registry& registry = plugins::Registry::global();
    std::vector<plugins::FormatInfo> formats;
    for (const auto kind : {plugins::OfferKind::MeasurementImport, plugins::OfferKind::SpectraImport,
                            plugins::OfferKind::IngredientImport}) {
        auto more = plugins::offeredFormats(registry, kind);
        formats.insert(formats.end(), more.begin(), more.end());
    }
    return formats;
}

// reset() first: it stops the timer that would show the dialog again (QProgressDialog's minimum duration).
void closeExportProgress(QProgressDialog* progress) {
    progress->reset();
    progress->hide();
}

}  // namespace

void MainWindow::addExchangeMenuItems(QMenu* file) {
    m_import_worker = new DatabaseWorker(this);
    m_appearance_export = new AppearanceExport(this);

    QAction* import = file->addAction(tr("&Import into database..."), this, [this]() {
        const auto chosen = chooseFileToOpen(this, QStringLiteral("database_import_dialog"),
                                             tr("Import a measurement, spectra or ingredients"),
                                             QStringLiteral("import/lastFolder"), importFormats());
        if (chosen) importIntoDatabase(chosen->path, chosen->format_id);
    });
    import->setObjectName("import_action");
    import->setStatusTip(tr("Store a measurement, spectra or ingredients from a file in any format the "
                            "plugins read (whole or nothing)"));

    QAction* appearance = file->addAction(tr("Export &appearance..."), this, [this]() {
        if (!m_document.hasRecipe()) {
            showError(tr("Cannot export the appearance"), tr("Open a recipe first."));
            return;
        }
        const auto chosen = chooseFileToSave(
            this, QStringLiteral("appearance_export_dialog"), tr("Export the recipe's appearance"),
            QStringLiteral("appearance/lastFolder"),
            plugins::offeredFormats(plugins::Registry::global(), plugins::OfferKind::AppearanceExport));
        if (!chosen) return;
        // A format that writes a painted object (glTF): which one.
        std::optional<std::string> object;
        const plugins::AppearanceExporter* exporter =
            plugins::Registry::global().exporterFor(chosen->path.toStdString(), chosen->format_id);
        if (exporter != nullptr && exporter->format().paints_object) {
            QInputDialog dialog(this);
            dialog.setObjectName(QStringLiteral("export_object_dialog"));
            dialog.setWindowTitle(tr("Painted object"));
            dialog.setLabelText(
                tr("The object painted with the recipe in %1:").arg(QFileInfo(chosen->path).fileName()));
            QStringList objects;
            for (const std::string_view name : plugins::kExportObjects)
                objects << QString::fromUtf8(name.data(), static_cast<int>(name.size()));
            dialog.setComboBoxItems(objects);
            dialog.setComboBoxEditable(false);
            if (dialog.exec() != QDialog::Accepted) return;
            object = dialog.textValue().toStdString();
        }
        exportAppearance(chosen->path, chosen->format_id, object);
    });
    appearance->setObjectName("export_appearance_action");
    appearance->setStatusTip(tr("Write the edited recipe's BRDF (fast model, standard preset) in a format "
                                "of the plugins: BRDF table, MERL, ..."));

    m_export_progress = new QProgressDialog(tr("Exporting the appearance..."), tr("Cancel"), 0, 1000, this);
    m_export_progress->setObjectName("appearance_export_progress");
    m_export_progress->setWindowTitle(tr("Export appearance"));
    m_export_progress->setWindowModality(Qt::NonModal);  // the workstation stays usable
    m_export_progress->setAutoClose(false);
    m_export_progress->setAutoReset(false);
    closeExportProgress(m_export_progress);
    connect(m_export_progress, &QProgressDialog::canceled, m_appearance_export, &AppearanceExport::cancel);
    connect(m_appearance_export, &AppearanceExport::progressed, this,
            [this](double fraction) { m_export_progress->setValue(static_cast<int>(1000.0 * fraction)); });
    connect(m_appearance_export, &AppearanceExport::writing, this, [this]() {
        m_export_progress->setRange(0, 0);  // busy until the exporter reports progress (if it does)
        m_export_progress->setLabelText(m_export_progress->labelText() +
                                        tr("\nThe fast model is done; writing the file."));
    });
    connect(m_appearance_export, &AppearanceExport::writeProgressed, this, [this](double fraction) {
        if (m_export_progress->maximum() == 0) m_export_progress->setRange(0, 1000);
        m_export_progress->setValue(static_cast<int>(1000.0 * fraction));
    });
    connect(m_appearance_export, &AppearanceExport::finished, this, [this](const QString& message) {
        closeExportProgress(m_export_progress);
        statusBar()->showMessage(message);
        emit appearanceExported(true, message);
    });
    connect(m_appearance_export, &AppearanceExport::failed, this, [this](const QString& message) {
        closeExportProgress(m_export_progress);
        showError(tr("Cannot export the appearance"), message);
        emit appearanceExported(false, message);
    });
    connect(m_appearance_export, &AppearanceExport::cancelled, this, [this]() {
        closeExportProgress(m_export_progress);
        const QString message = tr("Appearance export cancelled: no file written.");
        statusBar()->showMessage(message);
        emit appearanceExported(false, message);
    });
}

void MainWindow::importIntoDatabase(const QString& path, const std::optional<std::string>& format_id) {
    if (!m_db) {
        const QString message = tr("No database is open: %1 was not imported.").arg(path);
        showError(tr("Cannot import the file"), message);
        emit importFinished(false, message);
        return;
    }
    m_import_worker->setFile(m_db->file());
    statusBar()->showMessage(tr("Importing %1...").arg(path));
    const std::filesystem::path file = path.toStdString();
    // A recipe file is saved as a version: by the remembered author, else the login name.
    const QString remembered = rememberedAuthor();
    const std::string author = (remembered.isEmpty() ? loginName() : remembered).toStdString();
    m_import_worker->run<db::ImportResult>(
        [file, format_id, author](db::Database& db) {
            plugins::ImportRequest request;
            request.format_id = format_id;
            request.options.author = author;
            request.options.note = "imported from " + file.string();
            return plugins::importFile(db, file, request);
        },
        [this, path](const db::ImportResult& result) {
            const QString message = importedText(result, path);
            statusBar()->showMessage(message);
            m_ingredients->refresh();
            refreshMatchMeasurements();
            if (result.kind == db::ContentKind::Recipe) fillRecipeList();
            emit importFinished(true, message);
        },
        [this](const QString& message) {
            showError(tr("Cannot import the file"), message + tr("\n\nNothing of the file was stored."));
            emit importFinished(false, message);
        });
}

bool MainWindow::exportAppearance(const QString& path, const std::optional<std::string>& format_id,
                                  const std::optional<std::string>& object) {
    const auto refuse = [this](const QString& message) {
        showError(tr("Cannot export the appearance"), message);
        emit appearanceExported(false, message);
        return false;
    };
    if (!m_document.hasRecipe()) return refuse(tr("Open a recipe first."));
    if (m_appearance_export->running()) return refuse(tr("An export is running: wait for it or cancel it."));
    const std::filesystem::path file = path.toStdString();
    const plugins::Registry& registry = plugins::Registry::global();
    const plugins::AppearanceExporter* exporter = registry.exporterFor(file, format_id);
    if (exporter == nullptr)
        return refuse(
            tr("%1: cannot tell the format from the extension '%2': the appearance is exported as %3")
                .arg(path, QString::fromStdString(file.extension().string()),
                     QString::fromStdString(plugins::describeFormats(
                         plugins::offeredFormats(registry, plugins::OfferKind::AppearanceExport)))));
    plugins::ExportOptions options;
    options.recipe_path = currentLabel().toStdString();  // the file's provenance
    if (object) options.object = *object;
    m_appearance_export->start(m_document.recipe(), Preset::Standard, exporter, file, options);
    m_export_progress->setLabelText(
        tr("Exporting the appearance to %1 (%2)...")
            .arg(QFileInfo(path).fileName(), QString::fromStdString(exporter->format().description)));
    m_export_progress->setCancelButtonText(tr("Cancel"));
    m_export_progress->setRange(0, 1000);
    m_export_progress->setValue(0);
    m_export_progress->show();
    statusBar()->showMessage(tr("Exporting the appearance to %1...").arg(path));
    return true;
}

}  // namespace paintlab::gui
