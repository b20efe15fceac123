#include "recipe_ingredient.h"

#include "ingredient_fields.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace paintlab::gui {

namespace {

std::string label(const db::Ingredient& ingredient) {
    return ingredientKindLabel(ingredient.kind()) + " '" + ingredient.name + "'";
}

}  // namespace

Recipe withIngredient(const Recipe& recipe, int layer, const db::Ingredient& ingredient) {
    const std::string source = "ingredient " + label(ingredient);
    Recipe out = recipe;
    if (ingredient.kind() == db::IngredientKind::Substrate) {
        out.substrate = std::get<Substrate>(ingredient.data);
        validateRecipe(out, source);
        return out;
    }
    if (layer < 0 || layer >= static_cast<int>(out.layers.size()))
        throw InputError(source, "layer", "the recipe has no layer " + std::to_string(layer + 1));
    Layer& target = out.layers[static_cast<std::size_t>(layer)];
    std::visit(
        [&](const auto& data) {
            using T = std::decay_t<decltype(data)>;
            if constexpr (std::is_same_v<T, Binder>) {
                target.binder = data;
                target.binder.name = ingredient.name;
            } else if constexpr (!std::is_same_v<T, Substrate>) {
                for (const Component& c : target.components)
                    if (componentKind(c) == T::kKind && componentName(c) == ingredient.name)
                        throw InputError(source, "layer '" + target.name + "'",
                                         "the layer already holds it (change its volume fraction instead)");
                const double room = 1.0 - target.totalVolumeFraction();
                double fraction = std::min(kAddedVolumeFraction, room);
                if (ingredient.limits.max_volume_fraction)
                    fraction = std::min(fraction, *ingredient.limits.max_volume_fraction);
                if (!(fraction > 0.0))
                    throw InputError(source, "layer '" + target.name + "'",
                                     "no room is left in the layer (its volume fractions add up to 1)");
                T component = data;
                component.name = ingredient.name;
                // The size distribution is kept on the ingredient (its own column).
                if constexpr (std::is_same_v<T, MirrorFlake> || std::is_same_v<T, InterferenceFlake>)
                    component.diameter_sd_um = ingredient.diameter_sd_um;
                if (component.source.empty()) component.source = ingredient.source;
                component.volume_fraction = fraction;
                target.components.emplace_back(std::move(component));
            }
        },
        ingredient.data);
    validateRecipe(out, source);
    return out;
}

std::string additionText(const Recipe& recipe, int layer, const db::Ingredient& ingredient) {
    if (ingredient.kind() == db::IngredientKind::Substrate)
        return "Use " + label(ingredient) + " as substrate";
    const std::string layer_name = layer >= 0 && layer < static_cast<int>(recipe.layers.size())
                                       ? recipe.layers[static_cast<std::size_t>(layer)].name
                                       : std::to_string(layer + 1);
    if (ingredient.kind() == db::IngredientKind::Binder)
        return "Use " + label(ingredient) + " in '" + layer_name + "'";
    return "Add " + label(ingredient) + " to '" + layer_name + "'";
}

}  // namespace paintlab::gui
