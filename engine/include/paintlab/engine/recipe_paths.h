#pragma once
// The one way PaintLab names a field of a recipe in messages: the JSON
// file's keys, dotted, arrays indexed from 0, as the JSON reader reports them
// ("layers[1].components[0].volume_fraction", "substrate.reflectance").
// Names of layers and ingredients go in the message text, never in the path.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace paintlab {

// "parent.key", or "key" at the top level (parent "").
std::string fieldPath(std::string_view parent, std::string_view key);
// "parent.key[index]", an array's entry.
std::string elementPath(std::string_view parent, std::string_view key, std::size_t index);

std::string layerPath(std::size_t layer);                                // "layers[0]"
std::string binderPath(std::size_t layer);                               // "layers[0].binder"
std::string componentPath(std::size_t layer, std::size_t component);     // "layers[0].components[1]"
std::string depthProfilePath(std::size_t layer, std::size_t component);  // "...components[1].depth_profile"

// A path with the kind and name of what it holds, for messages about an
// ingredient: "layers[0].components[1] (pigment 'red')".
std::string ingredientLabel(std::string_view path, std::string_view kind, std::string_view name);

// A path split at its layer and component: "layers[1].components[0].volume_fraction"
// gives layer 1, component 0 and rest ".volume_fraction"; "layers[1].thickness_um"
// gives layer 1, no component and ".thickness_um". nullopt for a path outside
// the layers ("substrate.reflectance", "name").
struct LayerFieldPath {
    std::size_t layer = 0;
    std::optional<std::size_t> component;
    std::string rest;
};
std::optional<LayerFieldPath> splitLayerPath(std::string_view path);

}  // namespace paintlab
