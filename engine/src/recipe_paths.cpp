#include "paintlab/engine/recipe_paths.h"

#include <charconv>

namespace paintlab {

namespace {

// Reads "key[index]" at the start of text; advances text past it.
std::optional<std::size_t> takeIndex(std::string_view& text, std::string_view key) {
    if (text.substr(0, key.size()) != key || text.size() <= key.size() || text[key.size()] != '[')
        return std::nullopt;
    const char* first = text.data() + key.size() + 1;
    const char* last = text.data() + text.size();
    std::size_t index = 0;
    const auto [end, error] = std::from_chars(first, last, index);
    if (error != std::errc() || end == first || end == last || *end != ']') return std::nullopt;
    text.remove_prefix(static_cast<std::size_t>(end + 1 - text.data()));
    return index;
}

}  // namespace

std::string fieldPath(std::string_view parent, std::string_view key) {
    std::string path(parent);
    if (!path.empty()) path += '.';
    return path.append(key);
}

std::string elementPath(std::string_view parent, std::string_view key, std::size_t index) {
    return fieldPath(parent, key).append("[").append(std::to_string(index)).append("]");
}

std::string layerPath(std::size_t layer) { return elementPath("", "layers", layer); }

std::string binderPath(std::size_t layer) { return fieldPath(layerPath(layer), "binder"); }

std::string componentPath(std::size_t layer, std::size_t component) {
    return elementPath(layerPath(layer), "components", component);
}

std::string depthProfilePath(std::size_t layer, std::size_t component) {
    return fieldPath(componentPath(layer, component), "depth_profile");
}

std::string ingredientLabel(std::string_view path, std::string_view kind, std::string_view name) {
    std::string label(path);
    label.append(" (").append(kind).append(" '").append(name).append("')");
    return label;
}

std::optional<LayerFieldPath> splitLayerPath(std::string_view path) {
    const auto layer = takeIndex(path, "layers");
    if (!layer || (!path.empty() && !path.starts_with('.'))) return std::nullopt;
    LayerFieldPath out{*layer, std::nullopt, {}};
    if (std::string_view rest = path; rest.starts_with('.')) {
        rest.remove_prefix(1);
        if (const auto component = takeIndex(rest, "components");
            component && (rest.empty() || rest.starts_with('.'))) {
            out.component = component;
            path = rest;
        }
    }
    out.rest = std::string(path);
    return out;
}

}  // namespace paintlab
