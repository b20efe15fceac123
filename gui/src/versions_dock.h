#pragma once
// The saved versions of the recipe being edited (recipes.h): its history
// (version, author, time, note; the checksum as tooltip), saving a new
// version with a note, the differences between two versions (a table of the
// values that changed: path, old, new; recipe_diff.h), opening an old
// version in the editor and reverting to one, and rendering one beside the
// edited recipe (the render dock's comparison). Versions are immutable: a
// revert saves the old contents as a new version.
//
// Every operation is one or two small queries on the GUI thread's connection
// (a version is one recipe JSON of at most a few hundred kB).

#include "recipe_diff.h"
#include "recipe_document.h"

#include "paintlab/database/database.h"
#include "paintlab/database/recipes.h"

#include <QDockWidget>
#include <QString>

#include <functional>
#include <optional>
#include <vector>

class QLabel;
class QPushButton;
class QTableWidget;

namespace paintlab::gui {

class VersionsDock : public QDockWidget {
    Q_OBJECT
public:
    explicit VersionsDock(RecipeDocument* document, QWidget* parent = nullptr);

    void setDatabase(db::Database* database);
    // Asked before Open or Revert to replaces the edited recipe, with what is
    // about to happen ("opening version 2"); false: leave it as it is. By
    // default nothing is asked; the main window asks about unsaved edits.
    void setLeaveGuard(std::function<bool(const QString& next_step)> guard) {
        m_leave_guard = std::move(guard);
    }
    // Shows the history of the recipe of this name (the edited recipe's by default).
    void showRecipe(const QString& name);
    // Reads the history again.
    void refresh();
    const QString& recipeName() const { return m_name; }
    const std::vector<db::RecipeVersionInfo>& history() const { return m_history; }

    // Asks the main window to save the edited recipe as a new version (saveRequested).
    void saveNewVersion(const QString& note);
    // Fills the difference table with what changed from version a to version
    // b; false (and a message) if either cannot be read.
    bool diffVersions(int a, int b);
    const std::vector<RecipeChange>& lastDiff() const { return m_diff; }
    // Saves the contents of an old version as a new version (note "Revert to
    // version N"); returns the new version's number, or nullopt with a message
    // (nothing saved) if it cannot. When the latest version already has those
    // contents, nothing is saved and that version is returned.
    std::optional<int> revertTo(int version);
    // Loads a version into the editor (replacing unsaved edits without asking:
    // the Open button and a double-click ask the leave guard first).
    bool openVersion(int version);
    // Asks for a version to be rendered as the comparison (comparisonRequested);
    // false (and a message) if it cannot be read.
    bool compareInRender(int version);

    QTableWidget* historyTable() const { return m_table; }
    QTableWidget* diffTable() const { return m_diff_table; }

signals:
    void saveRequested(const QString& note);
    // A revert saved this version (the main window lists and opens it).
    void versionCreated(const QString& recipe, int version);
    // Render this recipe beside the edited one; label: "<name>, version <n>" (as the edited side's).
    void comparisonRequested(const paintlab::Recipe& recipe, const QString& label);

private:
    std::vector<int> selectedVersions() const;
    void askNoteAndSave();
    void diffSelected();
    void revertSelected();
    void updateButtons();
    void showError(const QString& title, const QString& message);

    bool mayLeave(const QString& next_step) const { return !m_leave_guard || m_leave_guard(next_step); }

    RecipeDocument* m_document;
    std::function<bool(const QString&)> m_leave_guard;
    db::Database* m_db = nullptr;
    QString m_name;
    std::vector<db::RecipeVersionInfo> m_history;
    std::vector<RecipeChange> m_diff;
    QLabel* m_title = nullptr;
    QTableWidget* m_table = nullptr;
    QPushButton* m_save = nullptr;
    QPushButton* m_compare = nullptr;
    QPushButton* m_open = nullptr;
    QPushButton* m_revert = nullptr;
    QPushButton* m_compare_render = nullptr;
    QLabel* m_diff_title = nullptr;
    QTableWidget* m_diff_table = nullptr;
};

}  // namespace paintlab::gui
