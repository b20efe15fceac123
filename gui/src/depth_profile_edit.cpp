#include "depth_profile_edit.h"

#include "paintlab/engine/parameters.h"
#include "paintlab/engine/recipe_paths.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>

namespace paintlab::gui {

namespace {

template <class RecipeT> auto* profileSlot(RecipeT& recipe, int layer, int component) {
    using Slot = std::conditional_t<std::is_const_v<RecipeT>, const std::optional<DepthProfile>,
                                    std::optional<DepthProfile>>;
    Slot* slot = nullptr;
    if (layer < 0 || layer >= static_cast<int>(recipe.layers.size())) return slot;
    auto& components = recipe.layers[static_cast<std::size_t>(layer)].components;
    if (component < 0 || component >= static_cast<int>(components.size())) return slot;
    std::visit(
        [&slot](auto& c) {
            if constexpr (requires { c.depth_profile; }) slot = &c.depth_profile;
        },
        components[static_cast<std::size_t>(component)]);
    return slot;
}

}  // namespace

DepthProfile presetProfile(DepthProfilePreset preset) {
    switch (preset) {
    case DepthProfilePreset::Uniform:
        return {{0.0, 1.0}, {1.0, 1.0}};
    case DepthProfilePreset::EnrichedTop:
        // Flakes or pigment floated to the surface (a leafing aluminium, a
        // surfactant-driven pigment): three times the concentration of the rest.
        return {{0.0, 0.2, 0.3, 1.0}, {3.0, 3.0, 1.0, 1.0}};
    case DepthProfilePreset::Settled:
        // Heavy particles sunk towards the substrate while the film was wet.
        return {{0.0, 0.7, 0.8, 1.0}, {1.0, 1.0, 3.0, 3.0}};
    case DepthProfilePreset::LinearGradient:
        return {{0.0, 1.0}, {0.5, 1.5}};
    }
    return {{0.0, 1.0}, {1.0, 1.0}};
}

DepthProfile shownProfile(const std::optional<DepthProfile>& stored) {
    return stored ? *stored : presetProfile(DepthProfilePreset::Uniform);
}

std::string depthProfileProblem(const DepthProfile& profile) {
    const RecipeProblem p = depthProfileNodeProblem(profile);
    if (p.message.empty()) return {};
    return (p.field.empty() ? std::string("depth_profile") : fieldPath("depth_profile", p.field)) + ": " +
           p.message;
}

DepthProfile withNodeMoved(const DepthProfile& profile, std::size_t node, double depth, double weight) {
    DepthProfile out = profile;
    if (node >= out.depth.size() || node >= out.weight.size()) return out;
    const bool end = node == 0 || node + 1 == out.depth.size();
    if (!end) {
        const double lo = out.depth[node - 1] + kMinNodeSpacing;
        const double hi = out.depth[node + 1] - kMinNodeSpacing;
        // Neighbours closer than two spacings (typed in, or from a file): keep the node where it was.
        if (lo <= hi) out.depth[node] = std::clamp(depth, lo, hi);
    }
    out.weight[node] = std::clamp(weight, params::kProfileWeight.min, params::kProfileWeight.max);
    return out;
}

std::optional<DepthProfile> withNodeInserted(const DepthProfile& profile, double depth, double weight,
                                             std::size_t* inserted_at) {
    if (!(depth > 0.0 && depth < 1.0) || profile.depth.size() != profile.weight.size()) return std::nullopt;
    const auto at = std::lower_bound(profile.depth.begin(), profile.depth.end(), depth);
    const auto index = static_cast<std::size_t>(at - profile.depth.begin());
    if (index < profile.depth.size() && profile.depth[index] - depth < kMinNodeSpacing) return std::nullopt;
    if (index > 0 && depth - profile.depth[index - 1] < kMinNodeSpacing) return std::nullopt;
    DepthProfile out = profile;
    const auto offset = static_cast<std::ptrdiff_t>(index);
    out.depth.insert(out.depth.begin() + offset, depth);
    out.weight.insert(out.weight.begin() + offset,
                      std::clamp(weight, params::kProfileWeight.min, params::kProfileWeight.max));
    if (inserted_at != nullptr) *inserted_at = index;
    return out;
}

std::optional<DepthProfile> withNodeRemoved(const DepthProfile& profile, std::size_t node) {
    if (node == 0 || node + 1 >= profile.depth.size() || node >= profile.weight.size()) return std::nullopt;
    DepthProfile out = profile;
    const auto offset = static_cast<std::ptrdiff_t>(node);
    out.depth.erase(out.depth.begin() + offset);
    out.weight.erase(out.weight.begin() + offset);
    return out;
}

std::optional<DepthProfile>* componentProfile(Recipe& recipe, int layer, int component) {
    return profileSlot(recipe, layer, component);
}

const std::optional<DepthProfile>* componentProfile(const Recipe& recipe, int layer, int component) {
    return profileSlot(recipe, layer, component);
}

Recipe withProfile(const Recipe& recipe, int layer, int component,
                   const std::optional<DepthProfile>& profile) {
    Recipe out = recipe;
    std::optional<DepthProfile>* slot = componentProfile(out, layer, component);
    if (slot == nullptr)
        throw std::out_of_range("layer " + std::to_string(layer + 1) + ", component " +
                                std::to_string(component + 1) + ": no component with a depth profile");
    *slot = profile;
    return out;
}

std::string profileEditError(const Recipe& current, const Recipe& candidate, int layer) {
    // A component's depth profile in this layer, or the layer's total volume fraction.
    auto aboutThisLayersProfiles = [layer](const std::string& field) {
        const std::optional<LayerFieldPath> path = splitLayerPath(field);
        if (!path || static_cast<int>(path->layer) != layer) return false;
        if (path->component) return path->rest.starts_with(".depth_profile");
        return path->rest == ".components";
    };
    std::set<std::pair<std::string, std::string>> already;
    for (const RecipeProblem& p : checkRecipe(current))
        if (p.severity == Severity::Error) already.insert({p.field, p.message});
    for (const RecipeProblem& p : checkRecipe(candidate))
        if (p.severity == Severity::Error &&
            (aboutThisLayersProfiles(p.field) || already.count({p.field, p.message}) == 0))
            return p.field + ": " + p.message;
    return {};
}

}  // namespace paintlab::gui
