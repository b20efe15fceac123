#include "production_dialog.h"

#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"

#include <QButtonGroup>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QRadioButton>
#include <QSettings>
#include <QSignalBlocker>
#include <QStandardPaths>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

namespace paintlab::gui {

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

struct Written {
    db::RecipeVersionInfo version;
    std::vector<std::string> warnings;
    int layers = 0;
};

QString extensionOf(db::FileFormat format) {
    const std::string_view name = db::fileFormatName(format);
    return QString::fromUtf8(name.data(), static_cast<int>(name.size()));
}

// "Blue pearl over black (two layers)" -> "Blue-pearl-over-black-two-layers"
QString fileStem(const QString& recipe) {
    QString out;
    for (const QChar c : recipe) {
        if (c.isLetterOrNumber()) {
            out += c;
        } else if (!out.endsWith('-')) {
            out += '-';
        }
    }
    while (out.endsWith('-')) out.chop(1);
    return out.isEmpty() ? QStringLiteral("recipe") : out;
}

// The first proposal's folder: Documents/PaintLab (made when the first sheet
// is written there), not the home folder's root; later the last one used.
QString defaultFolder() {
    return QDir(QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation)).filePath("PaintLab");
}

}  // namespace

ProductionDialog::ProductionDialog(db::Database* database, QWidget* parent)
    : QDialog(parent), m_db(database) {
    setObjectName("production_dialog");
    setWindowTitle(tr("Export production recipe"));
    auto* layout = new QVBoxLayout(this);
    auto* form = new QFormLayout;
    m_recipe = new QComboBox(this);
    m_recipe->setObjectName("production_recipe");
    m_version = new QComboBox(this);
    m_version->setObjectName("production_version");
    form->addRow(tr("Recipe"), m_recipe);
    form->addRow(tr("Version"), m_version);

    m_by_mass = new QRadioButton(tr("Batch of wet paint per layer"), this);
    m_by_area = new QRadioButton(tr("Painted area"), this);
    auto* group = new QButtonGroup(this);
    group->addButton(m_by_mass);
    group->addButton(m_by_area);
    m_batch_kg = new QDoubleSpinBox(this);
    m_batch_kg->setObjectName("production_batch_kg");
    m_batch_kg->setRange(0.001, 100000.0);
    m_batch_kg->setDecimals(3);
    m_batch_kg->setSuffix(" kg");
    m_area = new QDoubleSpinBox(this);
    m_area->setObjectName("production_area_m2");
    m_area->setRange(0.001, 1.0e6);
    m_area->setDecimals(3);
    m_area->setSuffix(" m²");
    m_efficiency = new QDoubleSpinBox(this);
    m_efficiency->setObjectName("production_transfer_efficiency");
    m_efficiency->setRange(0.01, 1.0);
    m_efficiency->setSingleStep(0.05);
    m_efficiency->setToolTip(tr("Share of the sprayed paint that lands on the part (1: no overspray)"));
    auto* mass_row = new QHBoxLayout;
    mass_row->addWidget(m_by_mass);
    mass_row->addWidget(m_batch_kg, 1);
    auto* area_row = new QHBoxLayout;
    area_row->addWidget(m_by_area);
    area_row->addWidget(m_area, 1);
    area_row->addWidget(new QLabel(tr("transfer efficiency"), this));
    area_row->addWidget(m_efficiency);
    form->addRow(tr("Batch"), mass_row);
    form->addRow(QString(), area_row);

    m_format = new QComboBox(this);
    m_format->setObjectName("production_format");
    m_format->addItem(tr("CSV (spreadsheets)"), static_cast<int>(db::FileFormat::Csv));
    m_format->addItem(tr("JSON"), static_cast<int>(db::FileFormat::Json));
    m_format->addItem(tr("HTML (printable sheet)"), static_cast<int>(db::FileFormat::Html));
    form->addRow(tr("Format"), m_format);
    auto* file_row = new QHBoxLayout;
    m_file = new QLineEdit(this);
    m_file->setObjectName("production_file");
    auto* browse = new QPushButton(tr("Browse..."), this);
    file_row->addWidget(m_file, 1);
    file_row->addWidget(browse);
    form->addRow(tr("File"), file_row);
    layout->addLayout(form);

    m_status = new QLabel(this);
    m_status->setObjectName("production_status");
    m_status->setWordWrap(true);
    m_status->setTextInteractionFlags(Qt::TextSelectableByMouse);
    layout->addWidget(m_status);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    m_export = buttons->addButton(tr("Export"), QDialogButtonBox::ActionRole);
    m_export->setObjectName("production_export");
    m_export->setDefault(true);
    layout->addWidget(buttons);

    // The last choices.
    const QSettings settings;
    m_batch_kg->setValue(settings.value("production/batchKg", 10.0).toDouble());
    m_area->setValue(settings.value("production/areaM2", 10.0).toDouble());
    m_efficiency->setValue(settings.value("production/transferEfficiency", 1.0).toDouble());
    (settings.value("production/byArea", false).toBool() ? m_by_area : m_by_mass)->setChecked(true);
    m_format->setCurrentIndex(std::clamp(settings.value("production/format", 0).toInt(), 0, 2));

    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(m_export, &QPushButton::clicked, this, &ProductionDialog::exportSheet);
    connect(browse, &QPushButton::clicked, this, &ProductionDialog::browse);
    connect(m_recipe, &QComboBox::currentIndexChanged, this, [this]() {
        fillVersions();
        setOutputFile({});
    });
    connect(m_version, &QComboBox::currentIndexChanged, this, [this]() { setOutputFile({}); });
    connect(m_format, &QComboBox::currentIndexChanged, this, [this]() { setFormat(format()); });
    connect(m_by_mass, &QRadioButton::toggled, this, &ProductionDialog::updateMode);
    connect(&m_worker, &DatabaseWorker::busyChanged, this,
            [this](bool busy) { m_export->setEnabled(!busy); });
    m_worker.setFile(database != nullptr ? database->file() : std::filesystem::path());
    fillRecipes();
    updateMode();
    setOutputFile({});
}

void ProductionDialog::fillRecipes() {
    const QSignalBlocker block(m_recipe);
    m_recipe->clear();
    if (m_db == nullptr) return;
    try {
        for (const db::RecipeSummary& r : db::listRecipes(*m_db)) m_recipe->addItem(qs(r.name), qs(r.name));
    } catch (const std::exception& e) {
        showError(tr("Cannot list the recipes"), QString::fromUtf8(e.what()));
    }
    fillVersions();
}

void ProductionDialog::fillVersions() {
    const QSignalBlocker block(m_version);
    m_version->clear();
    if (m_db == nullptr || m_recipe->currentIndex() < 0) return;
    try {
        const auto history = db::recipeHistory(*m_db, recipeName().toStdString());
        m_version->addItem(tr("latest (version %1)").arg(history.empty() ? 0 : history.back().version), 0);
        const std::vector<db::RecipeVersionInfo> newest_first(history.rbegin(), history.rend());
        for (const db::RecipeVersionInfo& v : newest_first) {
            QString text = tr("version %1, %2").arg(v.version).arg(qs(v.created_at));
            if (!v.note.empty()) text += QStringLiteral(": ") + qs(v.note);
            m_version->addItem(text, v.version);
        }
    } catch (const std::exception& e) {
        showError(tr("Cannot read the versions"), QString::fromUtf8(e.what()));
    }
}

bool ProductionDialog::setRecipe(const QString& name, std::optional<int> version) {
    fillRecipes();  // saved versions may have been added since the dialog was made
    const int index = m_recipe->findData(name);
    if (index < 0) return false;
    m_recipe->setCurrentIndex(index);
    fillVersions();
    const int v = m_version->findData(version.value_or(0));
    m_version->setCurrentIndex(v >= 0 ? v : 0);
    setOutputFile({});
    return true;
}

QString ProductionDialog::recipeName() const { return m_recipe->currentData().toString(); }

std::optional<int> ProductionDialog::version() const {
    const int v = m_version->currentData().toInt();
    return v > 0 ? std::optional(v) : std::nullopt;
}

void ProductionDialog::setBatchKg(double kg) {
    m_by_mass->setChecked(true);
    m_batch_kg->setValue(kg);
}

void ProductionDialog::setArea(double m2, double transfer_efficiency) {
    m_by_area->setChecked(true);
    m_area->setValue(m2);
    m_efficiency->setValue(transfer_efficiency);
}

db::FileFormat ProductionDialog::format() const {
    return static_cast<db::FileFormat>(m_format->currentData().toInt());
}

void ProductionDialog::setFormat(db::FileFormat format) {
    const int index = m_format->findData(static_cast<int>(format));
    if (index >= 0 && index != m_format->currentIndex()) {
        const QSignalBlocker block(m_format);
        m_format->setCurrentIndex(index);
    }
    const QString path = m_file->text();
    if (!path.isEmpty()) {
        const QFileInfo info(path);
        m_file->setText(info.dir().filePath(info.completeBaseName() + "." + extensionOf(this->format())));
    }
}

void ProductionDialog::setOutputFile(const QString& path) {
    if (!path.isEmpty()) {
        m_file->setText(path);
        return;
    }
    // A proposal: the last folder, named after the recipe and version.
    const QSettings settings;
    const QString folder = settings.value("production/lastFolder", defaultFolder()).toString();
    const std::optional<int> v = version();
    QString stem = fileStem(recipeName());
    if (v) stem += QStringLiteral("-v%1").arg(*v);
    m_file->setText(QDir(folder).filePath(stem + "-production." + extensionOf(format())));
}

QString ProductionDialog::outputFile() const { return m_file->text().trimmed(); }

db::ProductionOptions ProductionDialog::options() const {
    db::ProductionOptions options;
    if (m_by_mass->isChecked()) {
        options.batch_kg = m_batch_kg->value();
    } else {
        options.area_m2 = m_area->value();
        options.transfer_efficiency = m_efficiency->value();
    }
    return options;
}

void ProductionDialog::updateMode() {
    const bool mass = m_by_mass->isChecked();
    m_batch_kg->setEnabled(mass);
    m_area->setEnabled(!mass);
    m_efficiency->setEnabled(!mass);
}

void ProductionDialog::browse() {
    const db::FileFormat f = format();
    const QString filter = f == db::FileFormat::Csv    ? tr("CSV (*.csv)")
                           : f == db::FileFormat::Json ? tr("JSON (*.json)")
                                                       : tr("HTML (*.html)");
    const QString path = QFileDialog::getSaveFileName(this, tr("Production sheet"), outputFile(), filter);
    if (path.isEmpty()) return;
    setOutputFile(path);
    try {
        setFormat(db::formatOfFile(path.toStdString()));
    } catch (const std::exception&) {
        setFormat(f);  // no known extension: the chosen format's
    }
}

bool ProductionDialog::exportSheet() {
    const QString name = recipeName();
    const QString path = outputFile();
    if (name.isEmpty()) {
        showError(tr("Cannot export"), tr("No saved recipe is chosen (save a version first)."));
        return false;
    }
    if (path.isEmpty()) {
        showError(tr("Cannot export"), tr("No file is given."));
        return false;
    }
    const db::ProductionOptions production = options();
    try {
        db::validateProductionOptions(production);
    } catch (const std::exception& e) {
        showError(tr("Cannot export"), QString::fromUtf8(e.what()));
        return false;
    }
    if (QFileInfo(path).absolutePath() == defaultFolder()) QDir().mkpath(defaultFolder());
    saveSettings();
    const std::string recipe = name.toStdString();
    const std::optional<int> v = version();
    const db::FileFormat f = format();
    const std::filesystem::path file = path.toStdString();
    m_status->setText(tr("Writing %1...").arg(path));
    m_worker.run<Written>(
        [recipe, v, production, f, file](db::Database& db) {
            const db::ProductionSheet sheet = db::productionSheet(db, recipe, v, production);
            const std::string text = f == db::FileFormat::Csv    ? db::productionCsv(sheet)
                                     : f == db::FileFormat::Json ? db::productionJson(sheet)
                                                                 : db::productionHtml(sheet);
            io::writeFileAtomically(file, text);
            Written written{sheet.version, {}, static_cast<int>(sheet.layers.size())};
            for (const db::ProductionLayer& layer : sheet.layers)
                for (const std::string& w : layer.warnings) written.warnings.push_back(layer.name + ": " + w);
            return written;
        },
        [this, path](const Written& written) {
            QString summary =
                tr("Wrote the production sheet of '%1' version %2 (SHA-256 %3, %n layer(s)) to %4", nullptr,
                   written.layers)
                    .arg(qs(written.version.recipe_name))
                    .arg(written.version.version)
                    .arg(qs(written.version.checksum_sha256), path);
            for (const std::string& w : written.warnings) summary += "\n" + tr("Warning: %1").arg(qs(w));
            m_status->setText(summary);
            emit exported(path, summary);
        },
        [this](const QString& message) {
            m_status->setText(tr("Nothing was written."));
            showError(tr("Cannot export the production sheet"), message);
            emit exportFailed(message);
        });
    return true;
}

void ProductionDialog::saveSettings() const {
    QSettings settings;
    settings.setValue("production/batchKg", m_batch_kg->value());
    settings.setValue("production/areaM2", m_area->value());
    settings.setValue("production/transferEfficiency", m_efficiency->value());
    settings.setValue("production/byArea", m_by_area->isChecked());
    settings.setValue("production/format", m_format->currentIndex());
    const QString folder = QFileInfo(outputFile()).absolutePath();
    if (!folder.isEmpty()) settings.setValue("production/lastFolder", folder);
}

void ProductionDialog::done(int result) {
    saveSettings();
    QDialog::done(result);
}

void ProductionDialog::showError(const QString& title, const QString& message) {
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setObjectName("production_error");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

}  // namespace paintlab::gui
