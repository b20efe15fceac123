#pragma once
// Checks a recipe against the parameter declarations (parameters.h) and the
// rules that involve several fields: at least one layer, total volume
// fraction <= 1 at every depth, exactly one way of giving a mirror flake's
// reflectance, a well-formed depth profile.

#include "paintlab/engine/recipe.h"

#include <string>
#include <vector>

namespace paintlab {

enum class Severity { Warning, Error };

struct RecipeProblem {
    Severity severity = Severity::Error;
    std::string field;    // "layers[1].components[0].volume_fraction" (recipe_paths.h)
    std::string message;  // "0.4 is above the maximum 0.3 (allowed 0 to 0.3)"
};

// All problems found, errors and warnings (values outside the typical range,
// spectra that do not cover the visible range), in recipe order.
std::vector<RecipeProblem> checkRecipe(const Recipe& recipe);

// The problems of one material on its own, as the database stores an
// ingredient: every declared range (parameters.h) except the volume fraction,
// which a recipe gives, and a mirror flake's rule of a reflectance or the
// metal's n and k. Fields are the material's keys ("sigma_a_per_um",
// "reflectance"); the messages are checkRecipe's.
std::vector<RecipeProblem> checkMaterial(const Binder& binder);
std::vector<RecipeProblem> checkMaterial(const Component& component);
std::vector<RecipeProblem> checkMaterial(const Substrate& substrate);

// Throws InputError(source, field, message) for the first error; warnings pass.
void validateRecipe(const Recipe& recipe, const std::string& source);

// The first problem of a depth profile's nodes, its field relative to the
// profile ("depth[2]", "weight[1]", counted from 0, or "" for the profile as a
// whole) and an empty message when the nodes are well-formed: as many
// weights as depths, at least two nodes, depth strictly increasing from 0
// to 1, weights finite, >= 0 and within the declared maximum, not all zero.
// checkRecipe reports it under "...depth_profile."; the workstation's
// profile editor shows the same words while a node is dragged or typed.
RecipeProblem depthProfileNodeProblem(const DepthProfile& profile);

}  // namespace paintlab
