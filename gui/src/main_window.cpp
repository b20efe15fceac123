#include "main_window.h"

#include "accuracy_dock.h"
#include "author_setting.h"
#include "file_output.h"
#include "ingredient_dock.h"
#include "inplane_plot.h"
#include "match_dock.h"
#include "plots_dock.h"
#include "raymap_resolution.h"
#include "recipe_editor_dock.h"
#include "render_dock.h"
#include "undo_shortcut_filter.h"
#include "versions_dock.h"
#include "window_layout.h"
#include "workstation_paths.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/scene.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QScreen>
#include <QSettings>
#include <QStatusBar>
#include <QThread>
#include <QTimer>
#include <QUndoStack>

#include <exception>

namespace paintlab::gui {

namespace {

// The status bar's hint while no recipe is open.
QString pickHint() { return MainWindow::tr(": pick a recipe in the Recipes list to start"); }

}  // namespace

MainWindow::MainWindow(const WorkstationOptions& options, QWidget* parent) : QMainWindow(parent) {
    setWindowTitle(tr("PaintLab"));
    setObjectName("main_window");
    m_raymap_follows_view = options.raymap_follows_view;
    // The relit scene in the middle, the docks around it (window_layout.h).
    m_render = new RenderDock(this);
    setCentralWidget(m_render);
    m_recipes_dock = new QDockWidget(tr("Recipes"), this);
    m_recipes_dock->setObjectName("recipes");
    m_recipes = new QListWidget(m_recipes_dock);
    m_recipes->setObjectName("recipe_list");
    m_recipes_dock->setWidget(m_recipes);
    m_editor = new RecipeEditorDock(&m_document, this);
    m_accuracy = new AccuracyDock(this);
    m_inplane_dock = new QDockWidget(tr("In-plane BRDF"), this);
    m_inplane_dock->setObjectName("inplane");
    m_plot = new InplanePlot(m_inplane_dock);
    m_inplane_dock->setWidget(m_plot);
    addDatabaseDocks();
    addMatchDock();
    addPlotsDock();
    buildMenus();

    // A recipe picked in the list replaces the edited one: asked first if it has
    // unsaved edits. Queued: the question's dialog never runs inside the list's mouse handling.
    connect(
        m_recipes, &QListWidget::itemActivated, this,
        [this](QListWidgetItem* item) { pickRecipe(item->data(Qt::UserRole).toString()); },
        Qt::QueuedConnection);
    connect(
        m_recipes, &QListWidget::currentItemChanged, this,
        [this](QListWidgetItem* item) {
            if (item != nullptr) pickRecipe(item->data(Qt::UserRole).toString());
        },
        Qt::QueuedConnection);
    // Ctrl+Z and Ctrl+Shift+Z reach Edit > Undo / Redo from a number field too.
    qApp->installEventFilter(new UndoShortcutFilter(this, m_editor));
    connect(&m_draft, &RecoveryDraft::failed, this,
            [this](const QString& message) { statusBar()->showMessage(message); });
    connect(&m_document, &RecipeDocument::recipeChanged, this, &MainWindow::requestRender);
    // The first start's "pick a recipe" is done once one is loaded.
    connect(&m_document, &RecipeDocument::recipeLoaded, this, [this]() {
        if (statusBar()->currentMessage().endsWith(pickHint())) statusBar()->clearMessage();
    });
    connect(&m_scheduler, &RenderScheduler::finished, this, [this](const RenderResult& result) {
        m_render->showResult(result);
        m_accuracy->showResult(result, m_document.hasRecipe() ? &m_document.recipe() : nullptr);
        if (result.brdf) m_plot->setBrdf(*result.brdf);
    });
    connect(&m_scheduler, &RenderScheduler::failed, this,
            [this](quint64 /*generation*/, const QString& message) {
                showError(tr("Recompute failed"), message);
            });
    // The traced map refined in the background: each pass relights the recipe of the moment.
    connect(&m_refinement, &RayMapRefinement::passLanded, this,
            [this](int, std::shared_ptr<const raymaps::RayMap> map) {
                m_scheduler.setRayMap(std::move(map));
                m_compare_scheduler.shareRayMap(m_scheduler);
                requestRender(false);
            });
    // In its own corner of the status bar: messages and hints are not overwritten by it.
    auto* refinement_status = new QLabel(this);
    refinement_status->setObjectName("refinement_status");
    statusBar()->addPermanentWidget(refinement_status);
    connect(&m_refinement, &RayMapRefinement::statusChanged, refinement_status, &QLabel::setText);
    m_refine = options.refine_ray_map;
    connect(m_render, &RenderDock::exposureChanged, this, [this](double ev) {
        m_scheduler.setExposure(ev);
        m_compare_scheduler.setExposure(ev);
        requestRender(false);
    });
    connect(m_render, &RenderDock::saveImageRequested, this, &MainWindow::saveImage);
    connect(m_accuracy, &AccuracyDock::policyChanged, this, [this]() { requestRender(false); });
    // The verdict's "Compare with the full model": the Plots dock's own run.
    connect(m_accuracy, &AccuracyDock::fullModelRequested, this, [this]() {
        m_plots->show();
        m_plots->raise();
        m_plots->compareWithFullModel();
    });

    // First start: the default layout for the window's size; later the one the user left.
    resize(QSize(1366, 768).boundedTo(screen()->availableGeometry().size()));
    makeDocksScrollable(layoutDocks());
    restoreLayout(*this, layoutDocks());

    connectComparison();
    openDatabase(options.database);
    connectDatabaseDocks();
    // Once the window is shown and laid out: the ray map follows the view's size.
    if (options.open_scene)
        QTimer::singleShot(0, this, [this, scene = options.scene, raymap = options.raymap]() {
            openScene(scene.empty() ? demoScenePath() : scene, raymap);
        });
}

LayoutDocks MainWindow::layoutDocks() const {
    return {m_recipes_dock, m_editor, m_ingredients, m_accuracy,
            m_versions,     m_match,  m_plots,       m_inplane_dock};
}

MainWindow::~MainWindow() {
    if (m_trace != nullptr) {
        m_trace_cancel->store(true);
        m_trace->wait();
    }
}

void MainWindow::buildMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&Open recipe file..."), QKeySequence::Open, this, [this]() {
        const QString path =
            QFileDialog::getOpenFileName(this, tr("Open recipe"), {}, tr("Recipes (*.json)"));
        if (!path.isEmpty() && resolveUnsavedEdits(tr("opening %1").arg(path))) openRecipeFile(path);
    });
    file->addAction(tr("&Save version..."), QKeySequence::Save, this, &MainWindow::saveVersion);
    addDatabaseMenuItems(file);
    addExchangeMenuItems(file);
    file->addAction(tr("Open &scene..."), this, [this]() {
        const QString path = QFileDialog::getOpenFileName(this, tr("Open scene"), {}, tr("Scenes (*.json)"));
        if (!path.isEmpty()) openScene(path.toStdString(), {});
    });
    file->addAction(tr("Save &image..."), this, &MainWindow::saveImage);
    file->addAction(tr("Export plot data (CSV)..."), this, &MainWindow::exportPlotCsv);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = m_document.undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = m_document.undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    undo->setObjectName("undo_action");
    redo->setObjectName("redo_action");
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    QAction* author = edit->addAction(tr("&Author..."), this, [this]() {
        if (const auto name = askAuthor(this))
            statusBar()->showMessage(tr("Versions are saved by %1").arg(*name));
    });
    author->setObjectName("author_action");
    author->setStatusTip(tr("The name stored with every version you save"));

    QMenu* view = menuBar()->addMenu(tr("&View"));
    for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());
    QAction* reset =
        view->addAction(tr("&Reset layout"), this, [this]() { applyDefaultLayout(*this, layoutDocks()); });
    reset->setObjectName("reset_layout_action");
    // The ray map at the view's size now (raymap_resolution.h): the one cached for it, else traced.
    QAction* retrace = view->addAction(tr("Ray map for this &view size"), this, [this]() {
        if (!m_scene.empty()) openScene(m_scene, {});
    });
    retrace->setObjectName("raymap_for_view_action");
    retrace->setEnabled(m_raymap_follows_view);
    reset->setStatusTip(tr("Every dock back where it was at the first start, sized for this window"));
    view->addSeparator();
    QAction* log = view->addAction(tr("Logarithmic BRDF axis"));
    log->setCheckable(true);
    connect(log, &QAction::toggled, this, [this](bool on) { m_plot->setLogScale(on); });
}

void MainWindow::openDatabase(const std::filesystem::path& file) {
    try {
        m_db.emplace(db::Database::open(file.empty() ? db::defaultDatabasePath() : file));
        db::initDemoDatabase(*m_db);  // fills an empty database with the demo data, else nothing
        m_draft.setDatabase(m_db->file());
        fillRecipeList();
        statusBar()->showMessage(tr("Database %1").arg(QString::fromStdString(m_db->file().string())) +
                                 (m_document.hasRecipe() ? QString() : pickHint()));
    } catch (const std::exception& e) {
        m_db.reset();
        showError(tr("Cannot open the database"), QString::fromUtf8(e.what()));
    }
}

void MainWindow::fillRecipeList() {
    const QSignalBlocker block(m_recipes);
    m_recipes->clear();
    if (!m_db) return;
    for (const db::RecipeSummary& r : db::listRecipes(*m_db)) {
        auto* item = new QListWidgetItem(
            tr("%1 (v%2)").arg(QString::fromStdString(r.name)).arg(r.latest_version), m_recipes);
        item->setData(Qt::UserRole, QString::fromStdString(r.name));
    }
    // The edited recipe stays selected (a save refills the list).
    if (m_document.hasRecipe()) selectListItem(QString::fromStdString(m_document.recipe().name));
}

void MainWindow::selectListItem(const QString& name) {
    const QSignalBlocker block(m_recipes);
    for (int row = 0; row < m_recipes->count(); ++row)
        if (m_recipes->item(row)->data(Qt::UserRole).toString() == name) {
            m_recipes->setCurrentRow(row);
            return;
        }
    m_recipes->setCurrentRow(-1);  // a recipe not in the database (a file)
}

bool MainWindow::selectRecipe(const QString& name) {
    if (!m_db) return false;
    try {
        const db::StoredRecipeVersion stored = db::loadRecipeVersion(*m_db, name.toStdString());
        m_document.load(stored.recipe, tr("%1, version %2").arg(name).arg(stored.info.version),
                        stored.info.version);
        selectListItem(name);
        return true;
    } catch (const std::exception& e) {
        showError(tr("Cannot load the recipe"), QString::fromUtf8(e.what()));
        return false;
    }
}

bool MainWindow::openRecipeFile(const QString& path) {
    try {
        const Recipe recipe = loadRecipeFile(path.toStdString());
        m_document.load(recipe, path, 0);
        selectListItem({});
        addRecentFile(path);
        return true;
    } catch (const std::exception& e) {
        // InputError's text names the file, the field and the allowed range.
        showError(tr("Cannot open the recipe"), QString::fromUtf8(e.what()));
        return false;
    }
}

void MainWindow::openScene(const std::filesystem::path& scene, const std::filesystem::path& raymap) {
    m_refinement.cancel();  // the scene open before: none of its passes lands any more
    // A map traced now fills the view (raymap_resolution.h); the cache keeps one per view box.
    std::optional<PixelSize> box;
    if (m_raymap_follows_view && isVisible()) {
        const QSize view = m_render->viewPixels();
        box = rayMapBox({view.width(), view.height()});
    }
    m_scene = scene;
    const std::filesystem::path map_file =
        raymap.empty()
            ? cachedRayMapPath(scene, box ? QStringLiteral("-view%1x%2").arg(box->width).arg(box->height)
                                          : QString())
            : raymap;
    const auto openMap = [this, map_file, scene, refine = m_refine && raymap.empty()]() {
        try {
            std::shared_ptr<const raymaps::RayMap> map(raymaps::RayMap::open(map_file));
            m_scheduler.setRayMap(map);
            m_compare_scheduler.shareRayMap(m_scheduler);
            m_render->showMessage(tr("Ray map %1").arg(QString::fromStdString(map_file.string())));
            requestRender(false);
            if (refine) {
                // Passes at the opened map's own resolution (it may follow the view).
                RayMapRefinement::Limits limits;
                limits.camera_width = map->header().width;
                limits.camera_height = map->header().height;
                m_refinement.start(scene, std::filesystem::path(map_file).replace_extension(".refined.prm"),
                                   limits);
            }
        } catch (const std::exception& e) {
            showError(tr("Cannot open the ray map"), QString::fromUtf8(e.what()));
        }
    };
    if (std::filesystem::exists(map_file)) {
        openMap();
        return;
    }
    if (m_trace != nullptr) return;  // one trace at a time
    raymaps::Scene loaded;
    try {
        loaded = raymaps::loadSceneFile(scene);
        if (box) {
            const PixelSize size = rayMapResolution(*box, {loaded.camera.width, loaded.camera.height});
            loaded.camera.width = size.width;
            loaded.camera.height = size.height;
        }
    } catch (const std::exception& e) {
        showError(tr("Cannot open the scene"), QString::fromUtf8(e.what()));
        return;
    }
    // Tracing takes seconds: a worker thread, a progress dialog, and cancel.
    auto* progress = new QProgressDialog(tr("Tracing the scene once (only the paint is re-shaded later)..."),
                                         tr("Cancel"), 0, 1000, this);
    progress->setWindowModality(Qt::NonModal);
    progress->setMinimumDuration(500);
    progress->setObjectName("trace_progress");
    m_trace_cancel = std::make_shared<std::atomic<bool>>(false);
    auto fraction = std::make_shared<std::atomic<int>>(0);
    connect(progress, &QProgressDialog::canceled, this, [cancel = m_trace_cancel]() { cancel->store(true); });
    auto* poll = new QTimer(progress);
    connect(poll, &QTimer::timeout, progress,
            [progress, fraction]() { progress->setValue(fraction->load()); });
    poll->start(100);
    const auto cancel = m_trace_cancel;
    m_trace = QThread::create([this, loaded, map_file, cancel, fraction, progress, openMap]() {
        QString error;
        try {
            raymaps::buildRayMap(loaded, raymaps::RayMapSettings{}, map_file, [&](double f) {
                fraction->store(static_cast<int>(f * 1000.0));
                return !cancel->load();
            });
        } catch (const std::exception& e) {
            error = cancel->load() ? QString() : QString::fromUtf8(e.what());
        }
        const bool cancelled = cancel->load();
        QMetaObject::invokeMethod(
            this,
            [this, error, cancelled, progress, openMap]() {
                progress->deleteLater();
                m_trace->wait();
                m_trace->deleteLater();
                m_trace = nullptr;
                if (!error.isEmpty()) {
                    showError(tr("Cannot trace the scene"), error);
                } else if (cancelled) {
                    m_render->showMessage(tr("Tracing cancelled: no scene open"));
                } else {
                    openMap();
                }
            },
            Qt::QueuedConnection);
    });
    m_trace->start();
}

void MainWindow::requestRender(bool interactive) {
    if (!m_document.hasRecipe()) return;
    m_last_interactive = interactive;
    m_scheduler.setFollowPlan(m_accuracy->followPlan());
    m_last_preset = m_accuracy->presetFor(interactive);
    m_scheduler.request(m_document.recipe(), m_last_preset);
    m_refinement.setRecipe(m_document.recipe());
    requestComparison(false);
}

bool MainWindow::saveVersionAs(const QString& note) {
    if (!m_db || !m_document.hasRecipe()) return false;
    const std::optional<QString> author = authorForSave(this);
    if (!author) {
        statusBar()->showMessage(tr("Not saved: a version needs an author (Edit > Author...)"));
        return false;
    }
    try {
        db::SaveOptions options;
        options.author = author->toStdString();
        options.note = note.toStdString();
        options.source = m_document.origin().toStdString();
        const db::SavedVersion saved = db::saveRecipeVersion(*m_db, m_document.recipe(), options);
        fillRecipeList();
        emit versionSaved(QString::fromStdString(saved.recipe_name), saved.version);
        statusBar()->showMessage(
            saved.created
                ? tr("Saved %1 version %2").arg(QString::fromStdString(saved.recipe_name)).arg(saved.version)
                : tr("Unchanged: identical to version %1").arg(saved.version));
        return true;
    } catch (const std::exception& e) {
        showError(tr("Cannot save the version"), QString::fromUtf8(e.what()));
        return false;
    }
}

void MainWindow::saveImage() {
    const QImage image = m_render->imageToSave();  // what is shown: a comparison with its labels
    if (image.isNull()) return;
    const QString path = QFileDialog::getSaveFileName(this, tr("Save image"), {}, tr("Images (*.png)"));
    if (!path.isEmpty() && !saveImageAtomically(image, path))
        showError(tr("Cannot save the image"), tr("%1: cannot be written").arg(path));
}

void MainWindow::exportPlotCsv() {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export plot data"), {}, tr("CSV (*.csv)"));
    if (!path.isEmpty() && !m_plot->exportCsv(path))
        showError(tr("Cannot export the plot"), tr("%1: cannot be written").arg(path));
}

void MainWindow::showError(const QString& title, const QString& message) {
    statusBar()->showMessage(message);
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setObjectName("error_dialog");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();  // not exec(): the GUI thread never blocks on a dialog's own event loop
}

void MainWindow::addRecentFile(const QString& path) {
    QSettings settings;
    QStringList recent = settings.value("recentFiles").toStringList();
    recent.removeAll(path);
    recent.prepend(path);
    while (recent.size() > 10) recent.removeLast();
    settings.setValue("recentFiles", recent);
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!resolveUnsavedEdits(tr("closing PaintLab"))) {
        event->ignore();
        return;
    }
    saveLayout(*this);
    QMainWindow::closeEvent(event);
}

}  // namespace paintlab::gui
