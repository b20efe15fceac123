#pragma once
// Human-readable description of a recipe, for `paintlab-cli show`.

#include "paintlab/engine/recipe.h"

#include <string>

namespace paintlab::cli {

std::string describeRecipe(const Recipe& recipe);

}  // namespace paintlab::cli
