#pragma once
// The workstation's main window: the relit scene in the middle; the recipe
// list of the database, the recipe editor, the in-plane BRDF plot, the plots
// and accuracy docks around it (window_layout.h). Dock layout, window
// geometry and recent files are kept with QSettings. Unsaved edits are
// never dropped without asking (main_window_unsaved.cpp) and are kept in a
// recovery draft (recovery_draft.h) until saved or discarded.

#include "raymap_refinement.h"
#include "recipe_document.h"
#include "recovery_draft.h"
#include "render_scheduler.h"
#include "window_layout.h"

#include "paintlab/database/database.h"

#include <QMainWindow>

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

class QDockWidget;
class QListWidget;
class QMenu;
class QProgressDialog;
class QThread;

namespace paintlab::gui {

class AccuracyDock;
class AppearanceExport;
class DatabaseWorker;
class InplanePlot;
class MatchDock;
class PlotsDock;
class RecipeEditorDock;
class RenderDock;

struct WorkstationOptions {
    std::filesystem::path database;  // empty: the user's database (created from the demo)
    std::filesystem::path scene;     // empty: the demo scene
    std::filesystem::path raymap;    // empty: traced from the scene into the cache when missing
    bool open_scene = true;
    // A map traced at start takes the view's resolution (raymap_resolution.h);
    // false: the scene camera's own (tests' tiny scenes).
    bool raymap_follows_view = true;
    bool refine_ray_map = true;  // refine the traced map in the background (raymap_refinement.h)
};

// The database docks and dialog (main_window_docks.cpp).
class IngredientDock;
class ProductionDialog;
class VersionsDock;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const WorkstationOptions& options, QWidget* parent = nullptr);
    ~MainWindow() override;
    MainWindow(const MainWindow&) = delete;
    MainWindow& operator=(const MainWindow&) = delete;
    MainWindow(MainWindow&&) = delete;
    MainWindow& operator=(MainWindow&&) = delete;

    // Loads the latest saved version of a recipe of the database and selects
    // it in the recipe list; false (and a message box) if there is none of
    // that name. Replaces unsaved edits without asking: the user's ways there
    // (the recipe list, File > Open, a version opened) ask first (resolveUnsavedEdits).
    bool selectRecipe(const QString& name);
    // Loads a recipe file; false (and a message box naming the file and the field) if it is bad.
    // Replaces unsaved edits without asking, as selectRecipe.
    bool openRecipeFile(const QString& path);
    // Saves the edited recipe as the next version in the database, by the
    // remembered author (asked at the first save: author_setting.h); false if
    // no author is given or (with a message box) the database refuses it.
    bool saveVersionAs(const QString& note);

    // Before the edited recipe is replaced or the window closed: true at once
    // if there are no unsaved edits; otherwise asks (modal box
    // "unsaved_question": Save version... / Discard / Cancel). Save asks for
    // the version's note and saves; Discard removes the recovery draft. False:
    // cancelled (or the save failed), leave everything as it is.
    bool resolveUnsavedEdits(const QString& next_step);
    // A recovery draft left by an earlier run on this database (a crash, a
    // kill): asks (modal box "recovery_question": Restore / Discard) and, on
    // Restore, edits it as unsaved edits over the version they started from
    // (undo leads back to it). Call once at start, before any recipe is
    // loaded (loading one removes the draft). True if a draft was restored.
    bool offerRecoveredDraft();
    RecoveryDraft* recoveryDraft() { return &m_draft; }
    // "Blue pearl ..., version 2", "Blue pearl ..., modified since version 2",
    // "<file>, edited": the window title's and the render dock's name of the edited recipe.
    QString currentLabel();

    // The ingredient browser, the recipe versions and the production export
    // (main_window_docks.cpp): shows the non-modal dialog on the edited version.
    IngredientDock* ingredientDock() { return m_ingredients; }
    VersionsDock* versionsDock() { return m_versions; }
    ProductionDialog* openProductionDialog();

    RecipeDocument* document() { return &m_document; }
    RenderScheduler* scheduler() { return &m_scheduler; }
    AccuracyDock* accuracyDock() { return m_accuracy; }
    // The comparison shown beside the edited recipe in the render dock
    // (main_window_compare.cpp): rendered on its own scheduler, with the same
    // ray map, exposure, preset and plan setting as the edited recipe.
    void compareWith(const Recipe& recipe, const QString& label);
    void clearComparison();
    RenderScheduler* comparisonScheduler() { return &m_compare_scheduler; }
    RenderDock* renderDock() { return m_render; }
    RecipeEditorDock* editorDock() { return m_editor; }
    InplanePlot* plot() { return m_plot; }
    QListWidget* recipeList() { return m_recipes; }
    PlotsDock* plotsDock() { return m_plots; }
    MatchDock* matchDock() { return m_match; }

    // File > Import into database... after its dialog (main_window_exchange.cpp):
    // the file through the plugin registry (the importer of `format_id`,
    // else by extension and content; any kind: measurement, spectra,
    // ingredients, recipe), stored whole or not at all on a worker; then
    // importFinished. A bad file: a message naming it, nothing stored.
    void importIntoDatabase(const QString& path, const std::optional<std::string>& format_id = {});
    DatabaseWorker* importWorker() { return m_import_worker; }
    // File > Export appearance... after its dialog: the edited recipe's fast
    // model (standard preset) written by the registry's exporter of
    // `format_id`, else the one claiming the extension, on a thread with a
    // progress dialog; then appearanceExported. False (and a message) if it
    // cannot start: no recipe, no exporter for the file, an export running.
    // object: the painted object of a format that writes one (glTF; default sphere).
    bool exportAppearance(const QString& path, const std::optional<std::string>& format_id = {},
                          const std::optional<std::string>& object = {});
    AppearanceExport* appearanceExport() { return m_appearance_export; }

protected:
    void closeEvent(QCloseEvent* event) override;

signals:
    // saveVersionAs stored a version (or found the recipe identical to the latest one).
    void versionSaved(const QString& recipe, int version);
    // importIntoDatabase and exportAppearance ended (the message says what happened).
    void importFinished(bool ok, const QString& message);
    void appearanceExported(bool ok, const QString& message);

private:
    void buildMenus();
    void openDatabase(const std::filesystem::path& file);
    void fillRecipeList();
    void openScene(const std::filesystem::path& scene, const std::filesystem::path& raymap);
    void requestRender(bool interactive);
    // File > Save version...: asks for the note, then saveVersionAs; false if cancelled or failed.
    bool saveVersion();
    // A recipe picked in the list: asks about unsaved edits, then loads it
    // (or puts the list's selection back on the edited recipe).
    void pickRecipe(const QString& name);
    void selectListItem(const QString& name);
    void updateTitle();
    void saveImage();
    void exportPlotCsv();
    void showError(const QString& title, const QString& message);
    void addRecentFile(const QString& path);
    // The Plots dock and its wiring (main_window_plots.cpp).
    void addPlotsDock();
    // Ends the Plots dock's comparison if the render dock's comparison put it there.
    void clearPlotsComparisonFromRender();
    // The render dock's comparison and its wiring (main_window_compare.cpp).
    void connectComparison();
    // Renders the comparison again if it was rendered with other settings
    // than the edited recipe's last request (or `always`).
    void requestComparison(bool always);

    // The docks window_layout.h arranges.
    LayoutDocks layoutDocks() const;

    RecipeDocument m_document;
    RecoveryDraft m_draft{&m_document};
    RenderScheduler m_scheduler;
    RenderScheduler m_compare_scheduler;
    RayMapRefinement m_refinement;
    bool m_refine = true;
    std::optional<Recipe> m_comparison;
    // The label of the comparison the render dock put into the Plots dock
    // (empty: the plots' comparison, if any, is the user's own pin or the full model).
    QString m_plots_comparison_label;
    // What the comparison was last requested with: preset, plan, exposure, map.
    struct ComparisonKey {
        Preset preset = Preset::Standard;
        bool follow_plan = true;
        double exposure_ev = 0.0;
        const void* map = nullptr;
        bool operator==(const ComparisonKey&) const = default;
    };
    std::optional<ComparisonKey> m_comparison_key;
    Preset m_last_preset = Preset::Standard;
    std::optional<db::Database> m_db;
    QDockWidget* m_recipes_dock = nullptr;
    QListWidget* m_recipes = nullptr;
    QDockWidget* m_inplane_dock = nullptr;
    bool m_raymap_follows_view = true;
    std::filesystem::path m_scene;  // the scene last opened
    RecipeEditorDock* m_editor = nullptr;
    RenderDock* m_render = nullptr;
    AccuracyDock* m_accuracy = nullptr;
    InplanePlot* m_plot = nullptr;
    PlotsDock* m_plots = nullptr;
    bool m_last_interactive = false;
    // The scene being traced into a ray map, if any (cancelled and joined on close).
    QThread* m_trace = nullptr;
    std::shared_ptr<std::atomic<bool>> m_trace_cancel;

    // main_window_docks.cpp: the ingredient and versions docks, their menu
    // entries (recent files, production export) and their database.
    void addDatabaseDocks();
    void addDatabaseMenuItems(QMenu* file);
    void connectDatabaseDocks();
    IngredientDock* m_ingredients = nullptr;
    VersionsDock* m_versions = nullptr;
    ProductionDialog* m_production = nullptr;

    // main_window_match.cpp: the Match dock (a recipe fitted to a measurement).
    void addMatchDock();
    void refreshMatchMeasurements();
    // A BRDF measurement chosen in the Match dock: its in-plane samples on both in-plane plots.
    void showMeasuredSamples();
    // After an accepted fit was saved as a version: the fit's rows in the database.
    void recordMatchFit(const QString& note);
    MatchDock* m_match = nullptr;

    // main_window_exchange.cpp: File > Import into database... and Export
    // appearance..., with the plugin registry's formats (format_dialog.h).
    void addExchangeMenuItems(QMenu* file);
    DatabaseWorker* m_import_worker = nullptr;
    AppearanceExport* m_appearance_export = nullptr;
    QProgressDialog* m_export_progress = nullptr;
};

}  // namespace paintlab::gui
