#pragma once
// The structure edits of the recipe editor's layer list and component table:
// a layer added, removed, moved or renamed, a component removed or moved.
// Each gives the whole recipe after the edit and the text of its undo step
// (replace_recipe_command.h keeps the recipe before, so undo restores it
// exactly). Qt-free: the tests use it directly.
//
// Layers are in recipe order, top coat first (recipe.h); components in the
// order they are stored (the order of the production sheet and the editor).

#include "paintlab/engine/recipe.h"

#include <string>

namespace paintlab::gui {

struct StructureEdit {
    Recipe recipe;     // the recipe after the edit
    std::string text;  // the undo step: "Remove layer 'basecoat'"
};

// The thickness of a new layer: the declared default (params::kLayerThickness)
// if the declaration allows it, otherwise the middle of its typical range
// (the default is 0, which the declaration excludes: a thickness is required).
double newLayerThicknessUm();

// A clear lacquer for a new layer: no components, the binder of the recipe's
// first layer (the recipe editor has no database; a database binder is put in
// afterwards through the Ingredients dock), or the declared default binder
// (n 1.5, no absorption) when the recipe has no layer; the name "clear coat",
// or "clear coat 2", 3, ... when that is taken.
Layer newClearLayer(const Recipe& recipe);

// The functions below throw InputError naming the field ("layers[2]",
// "layers[1].components[3]") for an index that does not exist or a move
// past either end; they do not validate the result (checkStructureEdit does).

// A new clear layer inserted at index `at` (0: on top; layers.size(): at the bottom).
StructureEdit withLayerAdded(const Recipe& recipe, int at);
StructureEdit withLayerRemoved(const Recipe& recipe, int layer);
// Layer `layer` moved to index `to` (the others keep their order).
StructureEdit withLayerMoved(const Recipe& recipe, int layer, int to);
// Leading and trailing spaces are dropped. Also throws InputError when another
// layer has that name (layers are matched by name in version diffs).
StructureEdit withLayerRenamed(const Recipe& recipe, int layer, const std::string& name);
StructureEdit withComponentRemoved(const Recipe& recipe, int layer, int component);
StructureEdit withComponentMoved(const Recipe& recipe, int layer, int component, int to);

// Checks the edited recipe with the engine's validation (checkRecipe).
// Throws InputError(field, message) for the first error `candidate` has that
// `current` does not: errors are compared without the layers' and
// components' numbers and names, so that a move or a rename does not count
// an error `current` already had (a slider can leave a layer above 100 %) as
// new. Removing the only layer is refused so ("layers: the recipe has no
// layers; a paint needs at least one"), as is an empty name.
void checkStructureEdit(const Recipe& current, const Recipe& candidate);

}  // namespace paintlab::gui
