#pragma once
// The recipe being edited: its current value, where it came from (a saved
// version in the database or a file) and the undo stack of every edit.
// Edits go through undo commands (set_parameter_command.h), never around
// them, so that undo restores exactly what was there.

#include "paintlab/engine/recipe.h"

#include <QObject>
#include <QString>
#include <QUndoStack>

namespace paintlab::gui {

class RecipeDocument : public QObject {
    Q_OBJECT
public:
    explicit RecipeDocument(QObject* parent = nullptr);

    const Recipe& recipe() const { return m_recipe; }
    bool hasRecipe() const { return m_has_recipe; }
    // Where it came from: "Blue pearl over black (two layers), version 3" or a file name.
    const QString& origin() const { return m_origin; }
    int version() const { return m_version; }  // 0: not a saved version
    QUndoStack* undoStack() { return &m_undo; }
    // Edits not in the version or file it came from (the undo stack is not at its saved state).
    bool hasUnsavedEdits() const { return m_has_recipe && !m_undo.isClean(); }

    // A new recipe to edit: clears the undo history.
    void load(const Recipe& recipe, const QString& origin, int version);
    // For undo commands only: replaces the recipe without touching the history.
    void applyEdit(const Recipe& recipe, bool interactive);
    // The recipe as it is now was saved as this version: the origin and
    // version change, the recipe and the undo history stay (marked clean).
    void markSaved(const QString& origin, int version);
    // Numbers for drags (a slider, a depth-profile node), unique in the
    // process: the edits of one drag merge into one undo step, and an editor
    // rebuilt for the same field never merges a new drag into an old one
    // still on top of the undo stack.
    static int nextDragNumber();
    // An interactive edit (a slider drag) ended: announces the recipe again as final.
    void settle();
    // The layer chosen in the recipe editor's layer list (0 = top; -1: none),
    // which the Ingredients dock adds to. Not part of the recipe: no undo step.
    int selectedLayer() const { return m_selected_layer; }
    void setSelectedLayer(int layer);

signals:
    // interactive: the edit comes from a slider being dragged (the renderer
    // may use the preview preset and refine when it settles).
    void recipeChanged(bool interactive);
    void recipeLoaded();
    void selectedLayerChanged(int layer);

private:
    Recipe m_recipe;
    bool m_has_recipe = false;
    QString m_origin;
    int m_version = 0;
    int m_selected_layer = -1;
    QUndoStack m_undo;
};

}  // namespace paintlab::gui
