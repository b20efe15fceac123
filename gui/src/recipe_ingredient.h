#pragma once
// Putting a database ingredient into a recipe (the ingredient browser's
// "Add to layer"): a pigment or flake becomes a new component of the layer
// at a small volume fraction (1 %, less if its technological limit or the
// room left in the layer is smaller), a binder replaces the layer's binder,
// a substrate the recipe's substrate. Qt-free: the tests use it directly.

#include "paintlab/database/ingredients.h"
#include "paintlab/engine/recipe.h"

#include <string>

namespace paintlab::gui {

// The volume fraction a newly added pigment or flake starts at.
inline constexpr double kAddedVolumeFraction = 0.01;

// The recipe with the ingredient added to layer `layer` (0 = top). Throws
// InputError naming the ingredient (the layer does not exist, it already
// holds a component of that kind and name, no room is left) or, from
// validateRecipe, the field of the resulting recipe that is out of range.
Recipe withIngredient(const Recipe& recipe, int layer, const db::Ingredient& ingredient);

// What the addition does, for the undo step's text: "Add pigment 'carbon black' to 'basecoat'".
std::string additionText(const Recipe& recipe, int layer, const db::Ingredient& ingredient);

}  // namespace paintlab::gui
