// The main window's database docks (ingredient browser, recipe versions), the
// production export dialog and the recent-files menu: kept apart from
// main_window.cpp, which calls addDatabaseDocks(), addDatabaseMenuItems()
// and connectDatabaseDocks() once each.

#include "ingredient_dock.h"
#include "main_window.h"
#include "production_dialog.h"
#include "recipe_editor_dock.h"
#include "versions_dock.h"

#include "accuracy_dock.h"

#include <QAction>
#include <QFileInfo>
#include <QMenu>
#include <QSettings>
#include <QUndoStack>

namespace paintlab::gui {

void MainWindow::addDatabaseDocks() {
    // Placed by window_layout.h (restoreLayout): by default the ingredients a
    // tab beside the recipe editor, the versions beside the accuracy panel.
    m_ingredients = new IngredientDock(&m_document, this);
    m_versions = new VersionsDock(&m_document, this);

    // Opening or reverting to a version replaces the edited recipe: asked first.
    m_versions->setLeaveGuard([this](const QString& next_step) { return resolveUnsavedEdits(next_step); });
    connect(m_versions, &VersionsDock::saveRequested, this,
            [this](const QString& note) { saveVersionAs(note); });
    connect(this, &MainWindow::versionSaved, this, [this](const QString& recipe, int version) {
        // The edited recipe is now what the database holds as that version.
        m_document.markSaved(tr("%1, version %2").arg(recipe).arg(version), version);
        m_versions->refresh();
    });
    // A revert saved a new version: list it and edit it.
    connect(m_versions, &VersionsDock::versionCreated, this, [this](const QString& recipe) {
        fillRecipeList();
        selectRecipe(recipe);
    });
}

void MainWindow::addDatabaseMenuItems(QMenu* file) {
    // Recent recipe files, read from QSettings each time the menu opens (addRecentFile writes them).
    auto* recent = new QMenu(tr("Open &recent"), file);
    recent->setObjectName("recent_files_menu");
    connect(recent, &QMenu::aboutToShow, this, [this, recent]() {
        recent->clear();
        const QStringList files = QSettings().value("recentFiles").toStringList();
        for (const QString& path : files) {
            QAction* action = recent->addAction(QFileInfo(path).fileName(), this, [this, path]() {
                if (resolveUnsavedEdits(tr("opening %1").arg(path))) openRecipeFile(path);
            });
            action->setToolTip(path);
            action->setStatusTip(path);
        }
        if (files.isEmpty()) recent->addAction(tr("(none)"))->setEnabled(false);
    });
    // Right after "Open recipe file...".
    const QList<QAction*> actions = file->actions();
    file->insertMenu(actions.size() > 1 ? actions[1] : nullptr, recent);
    file->addAction(tr("Export &production recipe..."), this, [this]() { openProductionDialog(); });
}

void MainWindow::connectDatabaseDocks() {
    db::Database* database = m_db ? &*m_db : nullptr;
    m_ingredients->setDatabase(database);
    m_versions->setDatabase(database);
}

ProductionDialog* MainWindow::openProductionDialog() {
    if (m_production == nullptr) m_production = new ProductionDialog(m_db ? &*m_db : nullptr, this);
    // The version being edited if it has no unsaved edits, else the latest.
    if (m_document.hasRecipe()) {
        const bool saved = m_document.version() > 0 && m_document.undoStack()->isClean();
        m_production->setRecipe(QString::fromStdString(m_document.recipe().name),
                                saved ? std::optional(m_document.version()) : std::nullopt);
    }
    m_production->show();  // not modal: the workstation stays usable
    m_production->raise();
    m_production->activateWindow();
    return m_production;
}

}  // namespace paintlab::gui
