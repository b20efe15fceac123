#pragma once
// The ingredient browser and editor, on the database's ingredient repository
// (ingredients.h): the list of ingredients narrowed by a name search and a
// kind filter; the selected one's fields with their units (ingredient_fields.h),
// its literature sources, technological limits and spectra (table and
// preview chart); editing with validation (a bad value names the field in a
// message and nothing is saved); import and export of ingredient files in
// the formats of the plugin registry (format_dialog.h); and adding the
// selected ingredient to a layer of the recipe being edited (an undoable step).
//
// Searches (about 250 ms for 5000 ingredients), imports (files up to 64 MiB)
// and exports run on DatabaseWorkers; reading one ingredient (under 1 ms)
// and saving one (one transaction, 10-40 ms with its fsync) use the GUI
// thread's connection.

#include "database_worker.h"
#include "ingredient_fields.h"
#include "recipe_document.h"

#include "paintlab/database/database.h"
#include "paintlab/database/ingredients.h"

#include <QDockWidget>
#include <QString>

#include <map>
#include <optional>
#include <string>
#include <vector>

class QComboBox;
class QFormLayout;
class QLabel;
class QLineEdit;
class QPushButton;
class QTableWidget;
class QTimer;
class QTreeView;

namespace paintlab::gui {

class IngredientListModel;
class SpectrumChart;

class IngredientDock : public QDockWidget {
    Q_OBJECT
public:
    explicit IngredientDock(RecipeDocument* document, QWidget* parent = nullptr);

    // The GUI thread's connection (nullptr: none open); lists its ingredients.
    void setDatabase(db::Database* database);
    // Lists the ingredients matching the search and the kind filter again.
    // The search runs on a worker (with thousands of ingredients it takes
    // longer than the GUI thread may block); listed() follows.
    void refresh();
    // True while a search waits for the typing to pause or runs.
    bool searching() const;

    // Selects an ingredient of the list (false if it is not listed).
    bool selectIngredient(db::IngredientKind kind, const QString& name);
    // The selected ingredient as stored.
    const std::optional<db::Ingredient>& current() const { return m_current; }
    // The editor of a field (a QLineEdit, or a QPlainTextEdit for the
    // description) of the selected ingredient, by key ("density_g_cm3"); nullptr if none.
    QWidget* fieldEditor(const std::string& key) const;
    // Stores the edited fields. False, with a message naming the field (and
    // that field marked), if a value is not a number or out of its range; the
    // database is then unchanged.
    bool saveChanges();
    // Puts the fields back to the stored values.
    void revertChanges();
    // Adds the selected ingredient to the layer (0 = top) of the edited recipe,
    // as one undo step; false with a message if it does not fit.
    bool addToLayer(int layer);

    // Imports an ingredient file (whole or nothing) through the plugin
    // registry (plugins/exchange.h): the importer of `format_id`, else the
    // one the extension and content choose. Runs on the worker; the result
    // arrives later (importFinished). Errors name the file and the record.
    void importFile(const QString& path, const std::optional<std::string>& format_id = {});
    // Exports the listed ingredients (as filtered) with the registry's
    // exporter of `format_id`, else the one claiming the extension, on the
    // worker (exportFinished).
    void exportFile(const QString& path, const std::optional<std::string>& format_id = {});
    DatabaseWorker* worker() { return &m_worker; }

    QLineEdit* searchField() const { return m_search; }
    QComboBox* kindFilter() const { return m_kind; }
    QTreeView* list() const { return m_list; }
    // The listed ingredients, in list order.
    const std::vector<db::IngredientSummary>& listedIngredients() const;
    QTableWidget* spectraTable() const { return m_spectra; }
    SpectrumChart* chart() const { return m_chart; }
    QComboBox* layerChoice() const { return m_layer; }

signals:
    // The list shows the result of a search.
    void listed(int count);
    // An import or an edit changed the stored ingredients.
    void ingredientsChanged();
    void importFinished(bool ok, const QString& message);
    void exportFinished(bool ok, const QString& message);

private:
    void showList(std::vector<db::IngredientSummary> found);
    void showIngredient(std::optional<std::int64_t> id);
    void buildForm();
    void showSpectrum(int row);
    void markField(const std::string& key);
    void setModified(bool modified);
    void updateButtons();
    void fillLayers();
    void showError(const QString& title, const QString& message);
    void browseImport();
    void browseExport();

    RecipeDocument* m_document;
    db::Database* m_db = nullptr;
    QLineEdit* m_search = nullptr;
    QComboBox* m_kind = nullptr;
    QTimer* m_search_delay = nullptr;
    QTreeView* m_list = nullptr;
    IngredientListModel* m_model = nullptr;
    bool m_filling = false;  // the list is being replaced: no selection reaction
    QLabel* m_header = nullptr;
    QWidget* m_form_host = nullptr;
    QFormLayout* m_form = nullptr;
    QTableWidget* m_spectra = nullptr;
    SpectrumChart* m_chart = nullptr;
    QPushButton* m_save = nullptr;
    QPushButton* m_revert = nullptr;
    QPushButton* m_add = nullptr;
    QComboBox* m_layer = nullptr;
    QPushButton* m_import = nullptr;
    QPushButton* m_export = nullptr;
    QLabel* m_status = nullptr;

    std::optional<db::Ingredient> m_current;
    std::vector<db::StoredSpectrum> m_current_spectra;
    std::vector<IngredientField> m_fields;
    std::map<std::string, QWidget*> m_editors;
    bool m_modified = false;
    bool m_search_running = false;
    bool m_search_pending = false;
    // Last: destroyed (and joined) first. Searches and imports or exports
    // have a worker each, so a search is not queued behind a long import.
    DatabaseWorker m_reader;
    DatabaseWorker m_worker;
};

}  // namespace paintlab::gui
