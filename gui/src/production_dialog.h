#pragma once
// The production-recipe export: a saved recipe version, the batch (wet paint
// per layer in kg, or a painted area with the transfer efficiency of the
// application) and a format (CSV, JSON, printable HTML) give the production
// sheet of the database's production API (production.h), which names the
// recipe, its version and its SHA-256 checksum. The sheet is computed and
// written on a DatabaseWorker; the dialog is not modal and the last choices
// are kept with QSettings (the file is first proposed in Documents/PaintLab,
// then in the folder last written to).

#include "database_worker.h"

#include "paintlab/database/database.h"
#include "paintlab/database/exchange.h"
#include "paintlab/database/production.h"

#include <QDialog>
#include <QString>

#include <optional>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QRadioButton;

namespace paintlab::gui {

class ProductionDialog : public QDialog {
    Q_OBJECT
public:
    // database: the GUI thread's connection, for the lists of recipes and versions.
    explicit ProductionDialog(db::Database* database, QWidget* parent = nullptr);

    // Selects the recipe and version (nullopt: the latest); false if the recipe is not saved.
    bool setRecipe(const QString& name, std::optional<int> version = std::nullopt);
    void setBatchKg(double kg);
    void setArea(double m2, double transfer_efficiency);
    // Also gives the output file that extension.
    void setFormat(db::FileFormat format);
    void setOutputFile(const QString& path);
    QString outputFile() const;
    QString recipeName() const;
    std::optional<int> version() const;  // nullopt: the latest
    db::ProductionOptions options() const;

    // Starts writing the sheet (false, with a message, if the choices are
    // wrong); exported() or exportFailed() follows.
    bool exportSheet();
    DatabaseWorker* worker() { return &m_worker; }

signals:
    void exported(const QString& file, const QString& summary);
    void exportFailed(const QString& message);

protected:
    void done(int result) override;

private:
    void fillRecipes();
    void fillVersions();
    void browse();
    void updateMode();
    void saveSettings() const;
    void showError(const QString& title, const QString& message);
    db::FileFormat format() const;

    db::Database* m_db;
    QComboBox* m_recipe = nullptr;
    QComboBox* m_version = nullptr;
    QRadioButton* m_by_mass = nullptr;
    QRadioButton* m_by_area = nullptr;
    QDoubleSpinBox* m_batch_kg = nullptr;
    QDoubleSpinBox* m_area = nullptr;
    QDoubleSpinBox* m_efficiency = nullptr;
    QComboBox* m_format = nullptr;
    QLineEdit* m_file = nullptr;
    QPushButton* m_export = nullptr;
    QLabel* m_status = nullptr;
    DatabaseWorker m_worker;  // last: destroyed (and joined) first
};

}  // namespace paintlab::gui
