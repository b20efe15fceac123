#include "recipe_parameters.h"

#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>
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
    SliderRange range{lo, hi, isLogarithmic(decl) && hi > 0.0};
    // A logarithmic scale cannot reach 0: three decades below the top.
    if (range.log) range.lo = std::max(lo, hi * 1e-3);
    return range;
}

double SliderRange::position(double value) const {
    const double t = log ? std::log(std::max(value, lo) / lo) / std::log(hi / lo) : (value - lo) / (hi - lo);
    return std::clamp(t, 0.0, 1.0);
}

double SliderRange::valueAt(double position) const {
    const double t = std::clamp(position, 0.0, 1.0);
    return log ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t;
}

bool isLogarithmic(const ParameterDecl& decl) {
    const std::string_view key = decl.key;
    return key == "volume_fraction" || key.ends_with("thickness_um") || key.ends_with("thickness_nm");
}

DisplayUnit displayUnit(const ParameterDecl& decl) {
    if (decl.key == "volume_fraction") return {"%", 100.0};
    if (decl.unit == "1") return {"", 1.0};
    return {std::string(decl.unit), 1.0};
}

std::string displayText(const ParameterDecl& decl, double value) {
    const DisplayUnit unit = displayUnit(decl);
    std::string text = io::formatNumber(value * unit.scale);
    if (!unit.unit.empty()) text += " " + unit.unit;
    return text;
}

TypedValue checkTypedValue(const ParameterDecl& decl, const std::string& text) {
    const DisplayUnit unit = displayUnit(decl);
    std::string_view typed = text;
    const auto trim = [&typed]() {
        while (!typed.empty() && std::isspace(static_cast<unsigned char>(typed.front())) != 0)
            typed.remove_prefix(1);
        while (!typed.empty() && std::isspace(static_cast<unsigned char>(typed.back())) != 0)
            typed.remove_suffix(1);
    };
    trim();
    if (!unit.unit.empty() && typed.ends_with(unit.unit)) {
        typed.remove_suffix(unit.unit.size());  // "40 µm" typed with its unit
        trim();
    }
    std::string number(typed);
    // A decimal comma (a keyboard of another locale) when there is no point.
    if (number.find('.') == std::string::npos) std::replace(number.begin(), number.end(), ',', '.');
    if (!number.empty() && number.front() == '+') number.erase(0, 1);
    double shown = 0.0;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), shown);
    TypedValue out;
    if (number.empty() || error != std::errc() || end != number.data() + number.size() ||
        !std::isfinite(shown)) {
        out.message = "'" + text + "' is not a number";
        return out;
    }
    out.value = shown / unit.scale;
    const std::string label(decl.label);
    out.verdict = TypedValue::Verdict::Refuse;
    if (!decl.allows(out.value)) {
        const bool low = decl.minExclusive ? out.value <= decl.min : out.value < decl.min;
        out.message = low ? displayText(decl, out.value) + " is not allowed: " + label + " must be " +
                                (decl.minExclusive ? "above " : "at least ") + displayText(decl, decl.min)
                          : displayText(decl, out.value) + " is not allowed: " + label + " can be at most " +
                                displayText(decl, decl.max);
        return out;
    }
    out.verdict = TypedValue::Verdict::Apply;
    if (!decl.isTypical(out.value)) {
        out.verdict = TypedValue::Verdict::ApplyWithWarning;
        out.message = displayText(decl, out.value) + " is " +
                      (out.value < decl.typicalMin ? "below" : "above") + " the usual range, " +
                      io::formatNumber(decl.typicalMin * unit.scale) + "\u2013" +
                      displayText(decl, decl.typicalMax) + ": check it";
    }
    return out;
}

}  // namespace paintlab::gui
