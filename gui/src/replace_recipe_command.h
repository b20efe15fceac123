#pragma once
// One undoable edit that changes the recipe's structure (an ingredient added
// to a layer, a binder or substrate replaced): the whole recipe before and
// after is kept, so undo restores it exactly.

#include "recipe_document.h"

#include <QString>
#include <QUndoCommand>

namespace paintlab::gui {

class ReplaceRecipeCommand : public QUndoCommand {
public:
    ReplaceRecipeCommand(RecipeDocument* document, Recipe after, const QString& text);

    void undo() override;
    void redo() override;

private:
    RecipeDocument* m_document;
    Recipe m_before;
    Recipe m_after;
};

}  // namespace paintlab::gui
