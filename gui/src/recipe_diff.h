#pragma once
// What changed between two recipes (two saved versions, say): one entry per
// changed value with its path, the old and the new value. Computed on the
// canonical recipe JSON (recipe_json.h), the text a version's checksum is
// of, so every field counts, not only the editor's scalars. Layers and
// components are matched by name (and kind), not position, so removing a
// component does not show every later one as changed; a change of their
// order is one entry of its own. Qt-free: the tests use it directly.

#include "paintlab/engine/recipe.h"

#include <string>
#include <vector>

namespace paintlab::gui {

struct RecipeChange {
    // "layers[1] 'basecoat'.components[0] 'carbon black'.volume_fraction", "substrate.kind"
    std::string path;
    std::string old_value;  // kAbsent when the value was added
    std::string new_value;  // kAbsent when the value was removed
};

inline constexpr const char* kAbsent = "(absent)";

// In document order; empty when the recipes are equal.
std::vector<RecipeChange> diffRecipes(const Recipe& before, const Recipe& after);

}  // namespace paintlab::gui
