#include "replace_recipe_command.h"

#include <utility>

namespace paintlab::gui {

ReplaceRecipeCommand::ReplaceRecipeCommand(RecipeDocument* document, Recipe after, const QString& text)
    : m_document(document), m_before(document->recipe()), m_after(std::move(after)) {
    setText(text);
}

void ReplaceRecipeCommand::undo() { m_document->applyEdit(m_before, false); }

void ReplaceRecipeCommand::redo() { m_document->applyEdit(m_after, false); }

}  // namespace paintlab::gui
