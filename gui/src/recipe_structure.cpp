#include "recipe_structure.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/parameters.h"
#include "paintlab/engine/recipe_paths.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <cstddef>
#include <map>
#include <utility>

namespace paintlab::gui {

namespace {

// A layer's field path (recipe_paths.h); "layers" for a negative index.
std::string layerField(int layer) {
    return layer < 0 ? std::string("layers") : layerPath(static_cast<std::size_t>(layer));
}

// A component's field path; "layers[i].components" for a negative index.
std::string componentField(int layer, int component) {
    if (component < 0) return fieldPath(layerField(layer), "components");
    return elementPath(layerField(layer), "components", static_cast<std::size_t>(component));
}

// "interference flake 'pearl'", for undo texts.
std::string componentLabel(const Component& component) {
    std::string kind(componentKind(component));
    std::replace(kind.begin(), kind.end(), '_', ' ');
    return kind + " '" + componentName(component) + "'";
}

void checkLayerIndex(const Recipe& recipe, int layer) {
    if (layer < 0 || layer >= static_cast<int>(recipe.layers.size()))
        throw InputError("", layerField(layer),
                         "the recipe has no such layer (it has " + std::to_string(recipe.layers.size()) +
                             ")");
}

void checkComponentIndex(const Recipe& recipe, int layer, int component) {
    checkLayerIndex(recipe, layer);
    const Layer& l = recipe.layers[static_cast<std::size_t>(layer)];
    if (component < 0 || component >= static_cast<int>(l.components.size()))
        throw InputError("", componentField(layer, component),
                         "the layer has no such component (it has " + std::to_string(l.components.size()) +
                             ")");
}

template <class T> void moveElement(std::vector<T>& items, int from, int to) {
    const auto f = items.begin() + from;
    const auto t = items.begin() + to;
    if (from < to) {
        std::rotate(f, f + 1, t + 1);
    } else {
        std::rotate(t, f, f + 1);
    }
}

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return {};
    const auto last = text.find_last_not_of(" \t\r\n");
    return text.substr(first, last - first + 1);
}

// A problem's field without the indices of its layer and component, with
// the component's kind instead ("layers[1].components[0].volume_fraction"
// becomes "layers[].components[] (mirror_flake).volume_fraction"), so that
// the same problem is recognised after a structure edit moved it.
std::string anonymousField(const Recipe& recipe, const std::string& field) {
    const std::optional<LayerFieldPath> path = splitLayerPath(field);
    if (!path || path->layer >= recipe.layers.size()) return field;
    std::string anonymous = "layers[]";
    if (path->component) {
        const Layer& layer = recipe.layers[path->layer];
        if (*path->component >= layer.components.size()) return field;
        anonymous.append(".components[] (")
            .append(componentKind(layer.components[*path->component]))
            .append(")");
    }
    return anonymous + path->rest;
}

}  // namespace

double newLayerThicknessUm() {
    const ParameterDecl& decl = params::kLayerThickness;
    if (decl.allows(decl.defaultValue)) return decl.defaultValue;
    return 0.5 * (decl.typicalMin + decl.typicalMax);
}

Layer newClearLayer(const Recipe& recipe) {
    Layer layer;
    layer.thickness_um = newLayerThicknessUm();
    if (!recipe.layers.empty()) {
        layer.binder = recipe.layers.front().binder;
    } else {
        layer.binder.name = "clear binder";
        layer.binder.refractive_index = Spectrum(params::kBinderIndex.defaultValue);
        layer.binder.absorption_per_um = Spectrum(params::kBinderAbsorption.defaultValue);
    }
    auto taken = [&recipe](const std::string& name) {
        return std::any_of(recipe.layers.begin(), recipe.layers.end(),
                           [&name](const Layer& l) { return l.name == name; });
    };
    layer.name = "clear coat";
    for (int n = 2; taken(layer.name); ++n) layer.name = "clear coat " + std::to_string(n);
    return layer;
}

StructureEdit withLayerAdded(const Recipe& recipe, int at) {
    if (at < 0 || at > static_cast<int>(recipe.layers.size()))
        throw InputError("", "layers",
                         "a layer can go at positions 1 to " + std::to_string(recipe.layers.size() + 1) +
                             ", not " + std::to_string(at + 1));
    StructureEdit edit{recipe, {}};
    Layer layer = newClearLayer(recipe);
    edit.text = "Add layer '" + layer.name + "'";
    edit.recipe.layers.insert(edit.recipe.layers.begin() + at, std::move(layer));
    return edit;
}

StructureEdit withLayerRemoved(const Recipe& recipe, int layer) {
    checkLayerIndex(recipe, layer);
    StructureEdit edit{recipe, "Remove layer '" + recipe.layers[static_cast<std::size_t>(layer)].name + "'"};
    edit.recipe.layers.erase(edit.recipe.layers.begin() + layer);
    return edit;
}

StructureEdit withLayerMoved(const Recipe& recipe, int layer, int to) {
    checkLayerIndex(recipe, layer);
    if (to < 0 || to >= static_cast<int>(recipe.layers.size()))
        throw InputError("", layerField(layer),
                         to < 0 ? "it is already the top layer" : "it is already the bottom layer");
    const std::string& name = recipe.layers[static_cast<std::size_t>(layer)].name;
    StructureEdit edit{recipe, "Move layer '" + name + (to < layer ? "' up" : "' down")};
    moveElement(edit.recipe.layers, layer, to);
    return edit;
}

StructureEdit withLayerRenamed(const Recipe& recipe, int layer, const std::string& name) {
    checkLayerIndex(recipe, layer);
    const std::string new_name = trimmed(name);
    const std::string& old_name = recipe.layers[static_cast<std::size_t>(layer)].name;
    for (std::size_t l = 0; l < recipe.layers.size(); ++l)
        if (static_cast<int>(l) != layer && recipe.layers[l].name == new_name && !new_name.empty())
            throw InputError("", fieldPath(layerField(layer), "name"),
                             "layer " + std::to_string(l + 1) + " is already called '" + new_name +
                                 "'; layer names must differ");
    StructureEdit edit{recipe, "Rename layer '" + old_name + "' to '" + new_name + "'"};
    edit.recipe.layers[static_cast<std::size_t>(layer)].name = new_name;
    return edit;
}

StructureEdit withComponentRemoved(const Recipe& recipe, int layer, int component) {
    checkComponentIndex(recipe, layer, component);
    const Layer& l = recipe.layers[static_cast<std::size_t>(layer)];
    StructureEdit edit{recipe, "Remove " + componentLabel(l.components[static_cast<std::size_t>(component)]) +
                                   " from '" + l.name + "'"};
    auto& components = edit.recipe.layers[static_cast<std::size_t>(layer)].components;
    components.erase(components.begin() + component);
    return edit;
}

StructureEdit withComponentMoved(const Recipe& recipe, int layer, int component, int to) {
    checkComponentIndex(recipe, layer, component);
    const Layer& l = recipe.layers[static_cast<std::size_t>(layer)];
    if (to < 0 || to >= static_cast<int>(l.components.size()))
        throw InputError("", componentField(layer, component),
                         to < 0 ? "it is already the first component" : "it is already the last component");
    StructureEdit edit{recipe, "Move " + componentLabel(l.components[static_cast<std::size_t>(component)]) +
                                   (to < component ? " up" : " down") + " in '" + l.name + "'"};
    moveElement(edit.recipe.layers[static_cast<std::size_t>(layer)].components, component, to);
    return edit;
}

void checkStructureEdit(const Recipe& current, const Recipe& candidate) {
    // How many times each error (anonymous field, message) occurs in the current recipe.
    std::map<std::pair<std::string, std::string>, int> already;
    for (const RecipeProblem& p : checkRecipe(current))
        if (p.severity == Severity::Error) ++already[{anonymousField(current, p.field), p.message}];
    for (const RecipeProblem& p : checkRecipe(candidate)) {
        if (p.severity != Severity::Error) continue;
        int& count = already[{anonymousField(candidate, p.field), p.message}];
        if (count == 0) throw InputError("", p.field, p.message);
        --count;
    }
}

}  // namespace paintlab::gui
