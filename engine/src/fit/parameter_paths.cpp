#include "paintlab/engine/fit/parameter_paths.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_paths.h"

#include <string>
#include <type_traits>
#include <variant>

namespace paintlab::fit {

namespace {

// One field met in the traversal: a number (scalar or constant spectrum) or
// something a path may name but a fit cannot free (why_not says what).
struct Field {
    std::string path;
    std::string label;
    const ParameterDecl* decl = nullptr;
    double* scalar = nullptr;
    Spectrum* spectrum = nullptr;  // constant
    std::string why_not;           // empty: numeric
};

// Collects the fields of one struct through its traverse() hook.
class Collector {
public:
    Collector(std::vector<Field>& out, std::string path, std::string label)
        : m_out(out), m_path(std::move(path)), m_label(std::move(label)) {}

    void scalar(const ParameterDecl& decl, double& value) {
        m_out.push_back({fieldPath(m_path, decl.key), label(decl), &decl, &value, nullptr, {}});
    }
    void spectrum(const ParameterDecl& decl, Spectrum& value) {
        Field f{fieldPath(m_path, decl.key), label(decl), &decl, nullptr, nullptr, {}};
        if (value.isConstant())
            f.spectrum = &value;
        else
            f.why_not =
                "a tabulated spectrum (" + std::to_string(value.values().size()) + " values), not one number";
        m_out.push_back(std::move(f));
    }
    void optionalSpectrum(const ParameterDecl& decl, std::optional<Spectrum>& value) {
        if (value) spectrum(decl, *value);
    }

private:
    std::string label(const ParameterDecl& decl) const { return m_label + std::string(decl.label); }

    std::vector<Field>& m_out;
    std::string m_path;
    std::string m_label;
};

void collectProfile(std::vector<Field>& out, std::optional<DepthProfile>& profile, std::size_t l,
                    std::size_t c, const std::string& label) {
    if (!profile) return;
    const std::string base = depthProfilePath(l, c);
    for (std::size_t k = 0; k < profile->weight.size(); ++k)
        out.push_back({elementPath(base, "weight", k),
                       label + std::string(params::kProfileWeight.label) + " " + std::to_string(k),
                       &params::kProfileWeight,
                       &profile->weight[k],
                       nullptr,
                       {}});
    for (std::size_t k = 0; k < profile->depth.size(); ++k)
        out.push_back({elementPath(base, "depth", k),
                       {},
                       &params::kProfileDepth,
                       nullptr,
                       nullptr,
                       "a depth-profile depth: the depths' order is a constraint a fit does not keep"});
}

std::vector<Field> collect(Recipe& recipe) {
    std::vector<Field> out;
    out.push_back({"ambient.refractive_index",
                   "Ambient > " + std::string(params::kAmbientIndex.label),
                   &params::kAmbientIndex,
                   &recipe.ambient_refractive_index,
                   nullptr,
                   {}});
    for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
        Layer& layer = recipe.layers[l];
        const std::string layer_label = layer.name + " > ";
        Collector own(out, layerPath(l), layer_label);
        Layer::traverse(layer, own);
        Collector binder(out, binderPath(l), layer_label + "binder > ");
        Binder::traverse(layer.binder, binder);
        for (std::size_t c = 0; c < layer.components.size(); ++c) {
            const std::string label = layer_label + componentName(layer.components[c]) + " > ";
            Collector v(out, componentPath(l, c), label);
            std::visit(
                [&](auto& component) {
                    using T = std::remove_cvref_t<decltype(component)>;
                    T::traverse(component, v);
                    if constexpr (requires { component.depth_profile; })
                        collectProfile(out, component.depth_profile, l, c, label);
                },
                layer.components[c]);
        }
    }
    std::visit(
        [&](auto& substrate) {
            using T = std::remove_cvref_t<decltype(substrate)>;
            Collector v(out, "substrate", "Substrate > ");
            T::traverse(substrate, v);
        },
        recipe.substrate);
    return out;
}

ParameterPath describe(const Field& f) {
    ParameterPath p;
    p.path = f.path;
    p.label = f.label;
    p.decl = f.decl;
    p.value = f.scalar != nullptr ? *f.scalar : f.spectrum->values().front();
    p.min = f.decl->minExclusive ? f.decl->typicalMin : f.decl->min;
    p.max = f.decl->max;
    p.log_scale_suited = f.decl->unit == "µm" || f.decl->key == "volume_fraction";
    return p;
}

// Why a path names nothing in this recipe, as precisely as the path allows.
[[noreturn]] void throwMissing(const Recipe& recipe, std::string_view path) {
    const std::string field(path);
    if (const auto split = splitLayerPath(path)) {
        if (split->layer >= recipe.layers.size())
            throw InputError("<argument>", field,
                             "no such layer: the recipe has " + std::to_string(recipe.layers.size()) +
                                 " layers");
        const Layer& layer = recipe.layers[split->layer];
        if (split->component && *split->component >= layer.components.size())
            throw InputError("<argument>", field,
                             "no such component: layer " + std::to_string(split->layer) + " '" + layer.name +
                                 "' has " + std::to_string(layer.components.size()) + " components");
    }
    throw InputError("<argument>", field,
                     "not a numeric field of this recipe (`paintlab-cli fit --help TEMPLATE` lists them)");
}

Field& find(std::vector<Field>& fields, const Recipe& recipe, std::string_view path) {
    for (Field& f : fields) {
        if (f.path != path) continue;
        if (!f.why_not.empty())
            throw InputError("<argument>", std::string(path), "not a number: " + f.why_not);
        return f;
    }
    throwMissing(recipe, path);
}

}  // namespace

std::vector<ParameterPath> listParameterPaths(const Recipe& recipe) {
    Recipe copy = recipe;
    std::vector<ParameterPath> out;
    for (const Field& f : collect(copy))
        if (f.why_not.empty()) out.push_back(describe(f));
    return out;
}

ParameterPath describeParameter(const Recipe& recipe, std::string_view path) {
    Recipe copy = recipe;
    std::vector<Field> fields = collect(copy);
    return describe(find(fields, recipe, path));
}

double parameterValue(const Recipe& recipe, std::string_view path) {
    return describeParameter(recipe, path).value;
}

void setParameterValue(Recipe& recipe, std::string_view path, double value) {
    std::vector<Field> fields = collect(recipe);
    Field& f = find(fields, recipe, path);
    if (f.scalar != nullptr)
        *f.scalar = value;
    else
        *f.spectrum = Spectrum(value);
}

}  // namespace paintlab::fit
