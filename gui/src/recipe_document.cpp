#include "recipe_document.h"

namespace paintlab::gui {

RecipeDocument::RecipeDocument(QObject* parent) : QObject(parent) {}

void RecipeDocument::load(const Recipe& recipe, const QString& origin, int version) {
    m_recipe = recipe;
    m_has_recipe = true;
    m_origin = origin;
    m_version = version;
    m_undo.clear();
    emit recipeLoaded();
    emit recipeChanged(false);
}

void RecipeDocument::applyEdit(const Recipe& recipe, bool interactive) {
    m_recipe = recipe;
    emit recipeChanged(interactive);
}

void RecipeDocument::markSaved(const QString& origin, int version) {
    m_origin = origin;
    m_version = version;
    m_undo.setClean();
}

int RecipeDocument::nextDragNumber() {
    static int last = 0;  // GUI thread only
    return ++last;
}

void RecipeDocument::settle() { emit recipeChanged(false); }

void RecipeDocument::setSelectedLayer(int layer) {
    if (layer == m_selected_layer) return;
    m_selected_layer = layer;
    emit selectedLayerChanged(layer);
}

}  // namespace paintlab::gui
