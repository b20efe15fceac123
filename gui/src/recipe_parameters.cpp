#include "recipe_parameters.h"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace paintlab::gui {

namespace {

// A traversal visitor that lists scalar declarations or finds one field.
template <class Field> struct ScalarVisitor {
    const ParameterDecl* wanted = nullptr;  // nullptr: list them all
    std::vector<const ParameterDecl*> found;
    Field* field = nullptr;

    void scalar(const ParameterDecl& decl, Field& value) {
        if (wanted == nullptr) {
            found.push_back(&decl);
        } else if (wanted == &decl) {
            field = &value;
        }
    }
    template <class Spectrum> void spectrum(const ParameterDecl& /*decl*/, Spectrum& /*value*/) {}
    template <class Optional> void optionalSpectrum(const ParameterDecl& /*decl*/, Optional& /*value*/) {}
};

template <class RecipeT, class Field> Field* find(RecipeT& recipe, const ParameterRef& ref) {
    if (ref.layer < 0 || ref.layer >= static_cast<int>(recipe.layers.size())) return nullptr;
    auto& layer = recipe.layers[static_cast<std::size_t>(ref.layer)];
    ScalarVisitor<Field> v;
    v.wanted = ref.decl;
    if (ref.component < 0) {
        Layer::traverse(layer, v);
        return v.field;
    }
    if (ref.component >= static_cast<int>(layer.components.size())) return nullptr;
    std::visit(
        [&](auto& c) {
            using T = std::remove_cv_t<std::remove_reference_t<decltype(c)>>;
            T::traverse(c, v);
        },
        layer.components[static_cast<std::size_t>(ref.component)]);
    return v.field;
}

}  // namespace

std::vector<ParameterRef> editableParameters(const Recipe& recipe) {
    std::vector<ParameterRef> out;
    for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
        const Layer& layer = recipe.layers[l];
        ScalarVisitor<const double> own;
        Layer::traverse(layer, own);
        for (const ParameterDecl* d : own.found)
            out.push_back({static_cast<int>(l), -1, d, layer.name + " > " + std::string(d->label)});
        for (std::size_t c = 0; c < layer.components.size(); ++c) {
            ScalarVisitor<const double> v;
            std::visit(
                [&](const auto& comp) {
                    using T = std::remove_cv_t<std::remove_reference_t<decltype(comp)>>;
                    T::traverse(comp, v);
                },
                layer.components[c]);
            const std::string prefix = layer.name + " > " + componentName(layer.components[c]) + " > ";
            for (const ParameterDecl* d : v.found)
                out.push_back({static_cast<int>(l), static_cast<int>(c), d, prefix + std::string(d->label)});
        }
    }
    return out;
}

double* scalarField(Recipe& recipe, const ParameterRef& ref) { return find<Recipe, double>(recipe, ref); }

const double* scalarField(const Recipe& recipe, const ParameterRef& ref) {
    return find<const Recipe, const double>(recipe, ref);
}

SliderRange sliderRange(const ParameterDecl& decl, double value) {
    double lo = std::min(decl.typicalMin, value);
    double hi = std::max(decl.typicalMax, value);
    lo = std::max(lo, decl.min);
    hi = std::min(hi, decl.max);
    if (!(hi > lo)) hi = lo + 1.0;  // a degenerate declaration still gives a usable slider
    return {lo, hi};
}

}  // namespace paintlab::gui
