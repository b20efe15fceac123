#pragma once
// The edits the depth-profile editor makes to a component's concentration
// profile (recipe.h, DepthProfile), and the checks that keep an invalid
// profile out of the recipe. Qt-free: the tests use it directly.
//
// A profile's nodes are (depth, weight) pairs, depth 0 = top of the layer,
// 1 = bottom. The end nodes always sit at 0 and 1 (the engine requires it),
// so they can move only in weight and are never removed.

#include "paintlab/engine/recipe.h"

#include <cstddef>
#include <optional>
#include <string>

namespace paintlab::gui {

// What a lab would start from. Closed forms (w piecewise linear):
//   Uniform        w = 1                                 mean 1,   peak 1
//   EnrichedTop    3 over the top 20 %, ramp to 1 by 30 %  mean 1.5, peak 2
//   Settled        mirror image: 3 over the bottom 20 %    mean 1.5, peak 2
//   LinearGradient 0.5 at the top to 1.5 at the bottom     mean 1,   peak 1.5
enum class DepthProfilePreset { Uniform, EnrichedTop, Settled, LinearGradient };
DepthProfile presetProfile(DepthProfilePreset preset);

// The closest two nodes may be in relative depth, so that depths stay
// strictly increasing however a node is dragged (0.1 % of the layer).
inline constexpr double kMinNodeSpacing = 1e-3;

// What the editor shows: the stored profile, or the uniform one when there is none.
DepthProfile shownProfile(const std::optional<DepthProfile>& stored);

// The first problem of a profile's nodes (the engine's
// depthProfileNodeProblem, so an edit and a file get the same words), naming
// the field ("depth_profile.weight[1]: -0.5 is below 0"); empty when
// it is well-formed.
std::string depthProfileProblem(const DepthProfile& profile);

// Node `node` moved to (depth, weight): an end node keeps its depth, an inner
// node stays kMinNodeSpacing inside its neighbours, the weight is clipped to
// the declared range (an all-zero result is left for depthProfileProblem).
DepthProfile withNodeMoved(const DepthProfile& profile, std::size_t node, double depth, double weight);

// A node inserted at (depth, weight); nullopt when depth is not strictly
// inside (0, 1) or lies within kMinNodeSpacing of an existing node.
// *inserted_at receives its index.
std::optional<DepthProfile> withNodeInserted(const DepthProfile& profile, double depth, double weight,
                                             std::size_t* inserted_at);

// Node `node` removed; nullopt for an end node (or an index out of range).
std::optional<DepthProfile> withNodeRemoved(const DepthProfile& profile, std::size_t node);

// The profile slot of component `component` of layer `layer`; nullptr when
// there is no such component or its kind carries no profile (a raw medium).
std::optional<DepthProfile>* componentProfile(Recipe& recipe, int layer, int component);
const std::optional<DepthProfile>* componentProfile(const Recipe& recipe, int layer, int component);

// The recipe with that component's profile replaced (nullopt: uniform).
// Throws std::out_of_range if the component has no profile slot.
Recipe withProfile(const Recipe& recipe, int layer, int component,
                   const std::optional<DepthProfile>& profile);

// Why `candidate` (`current` with a profile in layer `layer` edited) may not
// replace `current`, as "field: message" from the engine's validation
// (checkRecipe); empty when it may. Refused: any error about a depth profile
// or the local total volume fraction of that layer (a peak above a
// component's technological limit, a local total above 100 %), even one
// `current` already had (a concentration slider can leave the recipe so:
// only an edit that mends it is taken), and any error elsewhere that
// `current` does not have with the same message.
std::string profileEditError(const Recipe& current, const Recipe& candidate, int layer);

}  // namespace paintlab::gui
