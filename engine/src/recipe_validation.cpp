#include "paintlab/engine/recipe_validation.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/recipe_paths.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace paintlab {

namespace {

using io::formatNumber;

std::string rangeText(const ParameterDecl& decl) {
    // Built with append: GCC 12 warns falsely (-Wrestrict) on chained operator+ here.
    std::string text = decl.minExclusive ? "above " : "";
    text.append(formatNumber(decl.min)).append(" to ").append(formatNumber(decl.max));
    if (decl.unit != "1") text.append(" ").append(decl.unit);
    return text;
}

// The visitor that checks every declared field against its declaration.
// Without a volume fraction: a material as the database stores it, before a
// recipe gives it an amount.
enum class VolumeFraction { Check, Skip };

class FieldChecker {
public:
    FieldChecker(std::vector<RecipeProblem>& problems, std::string path,
                 VolumeFraction volume_fraction = VolumeFraction::Check)
        : m_problems(problems), m_path(std::move(path)), m_volume_fraction(volume_fraction) {}

    void scalar(const ParameterDecl& decl, double value) {
        if (m_volume_fraction == VolumeFraction::Skip && decl.key == "volume_fraction") return;
        checkValue(decl, value, field(decl), "");
    }

    void spectrum(const ParameterDecl& decl, const Spectrum& s) {
        const std::string where = field(decl);
        for (std::size_t i = 0; i < s.values().size(); ++i) {
            const std::string at = s.isConstant() ? "" : " at " + formatNumber(s.wavelengthsNm()[i]) + " nm";
            if (!checkValue(decl, s.values()[i], where, at)) return;  // one message per spectrum is enough
        }
        if (!s.isConstant() &&
            (s.wavelengthsNm().front() > kVisibleMinNm || s.wavelengthsNm().back() < kVisibleMaxNm))
            add(Severity::Warning, where,
                "tabulated from " + formatNumber(s.wavelengthsNm().front()) + " to " +
                    formatNumber(s.wavelengthsNm().back()) +
                    " nm only; held constant beyond, up to 380-780 nm");
    }

    void optionalSpectrum(const ParameterDecl& decl, const std::optional<Spectrum>& s) {
        if (s) spectrum(decl, *s);
    }

private:
    std::string field(const ParameterDecl& decl) const { return fieldPath(m_path, decl.key); }

    void add(Severity severity, const std::string& where, std::string message) {
        m_problems.push_back({severity, where, std::move(message)});
    }

    bool checkValue(const ParameterDecl& decl, double value, const std::string& where,
                    const std::string& at) {
        if (!std::isfinite(value)) {
            add(Severity::Error, where, "value" + at + " is not a finite number");
            return false;
        }
        if (!decl.allows(value)) {
            const bool below = decl.minExclusive ? value <= decl.min : value < decl.min;
            const std::string limit = below
                                          ? (decl.minExclusive ? "must be above " : "is below the minimum ") +
                                                formatNumber(decl.min)
                                          : "is above the maximum " + formatNumber(decl.max);
            add(Severity::Error, where,
                formatNumber(value) + at + " " + limit + " (allowed " + rangeText(decl) + ")");
            return false;
        }
        if (!decl.isTypical(value) && at.empty())
            add(Severity::Warning, where,
                formatNumber(value) + " is outside the typical range " + formatNumber(decl.typicalMin) +
                    " to " + formatNumber(decl.typicalMax));
        return true;
    }

    std::vector<RecipeProblem>& m_problems;
    std::string m_path;
    VolumeFraction m_volume_fraction;
};

void checkDepthProfile(const DepthProfile& profile, const std::string& path, double volume_fraction,
                       double max_volume_fraction, std::vector<RecipeProblem>& problems) {
    const std::string where = fieldPath(path, "depth_profile");
    if (RecipeProblem node = depthProfileNodeProblem(profile); !node.message.empty()) {
        node.field = node.field.empty() ? where : fieldPath(where, node.field);
        problems.push_back(std::move(node));
        return;
    }
    // The nodes are in range: the weights' typical-range warnings, and the peak.
    FieldChecker checker(problems, where);
    for (double w : profile.weight) checker.scalar(params::kProfileWeight, w);
    const double peak = volume_fraction * profile.peakRelativeConcentration();
    if (peak > max_volume_fraction)
        problems.push_back({Severity::Error, where,
                            "the profile's peak volume fraction " + formatNumber(peak) +
                                " is above the maximum " + formatNumber(max_volume_fraction)});
}

// A component's profile if it has a well-formed one: a malformed profile's
// problem is reported already and must not throw from the profile's maths.
const DepthProfile* wellFormedProfile(const Component& c) {
    const auto* p = componentDepthProfile(c);
    if (p == nullptr || !p->has_value() || !depthProfileNodeProblem(**p).message.empty()) return nullptr;
    return &**p;
}

// Local total volume fraction at every depth where some profile has a sample
// (the sum of piecewise-linear functions peaks at one of their nodes).
double peakTotalVolumeFraction(const Layer& layer) {
    std::set<double> depths{0.0, 1.0};
    for (const auto& c : layer.components)
        if (const DepthProfile* p = wellFormedProfile(c)) depths.insert(p->depth.begin(), p->depth.end());
    double peak = 0.0;
    for (double z : depths) {
        double total = 0.0;
        for (const auto& c : layer.components) {
            const DepthProfile* p = wellFormedProfile(c);
            const double shape = p != nullptr ? p->weightAt(z) / p->meanWeight() : 1.0;
            total += componentVolumeFraction(c) * shape;
        }
        peak = std::max(peak, total);
    }
    return peak;
}

// A material's declared fields and the rules within one material (a mirror
// flake's reflectance or the metal's n and k).
template <class T> void checkMaterialFields(const T& c, const std::string& path,
                                            VolumeFraction volume_fraction,
                                            std::vector<RecipeProblem>& problems) {
    FieldChecker checker(problems, path, volume_fraction);
    T::traverse(c, checker);
    if constexpr (std::is_same_v<T, MirrorFlake>) {
        const bool has_nk = c.metal_n.has_value() || c.metal_k.has_value();
        if (c.reflectance.has_value() == has_nk)
            problems.push_back(
                {Severity::Error, fieldPath(path, "reflectance"),
                 "give either 'reflectance' or the metal's 'n' and 'k', exactly one of the two"});
        else if (has_nk && (!c.metal_n || !c.metal_k))
            problems.push_back({Severity::Error, fieldPath(path, c.metal_n ? "k" : "n"),
                                "a metal's complex index needs both 'n' and 'k'"});
    }
}

template <class T>
void checkComponent(const T& c, const std::string& path, std::vector<RecipeProblem>& problems) {
    if (c.name.empty())
        problems.push_back({Severity::Error, fieldPath(path, "name"), "the component needs a name"});
    checkMaterialFields(c, path, VolumeFraction::Check, problems);
    if constexpr (requires { c.depth_profile; }) {
        if (c.depth_profile) {
            const ParameterDecl& decl = std::is_same_v<T, Pigment> ? params::kPigmentVolumeFraction
                                        : std::is_same_v<T, MirrorFlake>
                                            ? params::kMirrorVolumeFraction
                                            : params::kInterferenceVolumeFraction;
            checkDepthProfile(*c.depth_profile, path, c.volume_fraction, decl.max, problems);
        }
    }
}

void checkLayer(const Layer& layer, std::size_t index, std::vector<RecipeProblem>& problems) {
    const std::string path = layerPath(index);
    if (layer.name.empty())
        problems.push_back({Severity::Error, fieldPath(path, "name"), "the layer needs a name"});
    FieldChecker checker(problems, path);
    Layer::traverse(layer, checker);
    FieldChecker binder_checker(problems, binderPath(index));
    Binder::traverse(layer.binder, binder_checker);
    for (std::size_t i = 0; i < layer.components.size(); ++i) {
        const std::string where = componentPath(index, i);
        std::visit([&](const auto& c) { checkComponent(c, where, problems); }, layer.components[i]);
    }
    const double total = layer.totalVolumeFraction();
    if (total > 1.0) {
        problems.push_back({Severity::Error, fieldPath(path, "components"),
                            "total volume fraction " + formatNumber(total) + " (" +
                                formatNumber(100.0 * total) + "%) is above 1 (100%)"});
    } else if (const double peak = peakTotalVolumeFraction(layer); peak > 1.0) {
        problems.push_back({Severity::Error, fieldPath(path, "components"),
                            "with the depth profiles the local total volume fraction reaches " +
                                formatNumber(peak) + ", above 1 (100%)"});
    }
}

}  // namespace

std::vector<RecipeProblem> checkRecipe(const Recipe& recipe) {
    std::vector<RecipeProblem> problems;
    if (recipe.name.empty()) problems.push_back({Severity::Error, "name", "the recipe needs a name"});
    FieldChecker(problems, "ambient").scalar(params::kAmbientIndex, recipe.ambient_refractive_index);
    if (recipe.layers.empty())
        problems.push_back(
            {Severity::Error, "layers", "the recipe has no layers; a paint needs at least one"});
    for (std::size_t i = 0; i < recipe.layers.size(); ++i) checkLayer(recipe.layers[i], i, problems);
    std::visit(
        [&problems](const auto& s) {
            FieldChecker checker(problems, "substrate");
            std::decay_t<decltype(s)>::traverse(s, checker);
        },
        recipe.substrate);
    return problems;
}

std::vector<RecipeProblem> checkMaterial(const Binder& binder) {
    std::vector<RecipeProblem> problems;
    checkMaterialFields(binder, "", VolumeFraction::Skip, problems);
    return problems;
}

std::vector<RecipeProblem> checkMaterial(const Component& component) {
    std::vector<RecipeProblem> problems;
    std::visit([&](const auto& c) { checkMaterialFields(c, "", VolumeFraction::Skip, problems); }, component);
    return problems;
}

std::vector<RecipeProblem> checkMaterial(const Substrate& substrate) {
    std::vector<RecipeProblem> problems;
    std::visit([&](const auto& s) { checkMaterialFields(s, "", VolumeFraction::Skip, problems); }, substrate);
    return problems;
}

void validateRecipe(const Recipe& recipe, const std::string& source) {
    for (const auto& problem : checkRecipe(recipe))
        if (problem.severity == Severity::Error) throw InputError(source, problem.field, problem.message);
}

namespace {

std::string nodeField(const char* field, std::size_t i) { return elementPath("", field, i); }

}  // namespace

RecipeProblem depthProfileNodeProblem(const DepthProfile& profile) {
    const std::vector<double>& z = profile.depth;
    const std::vector<double>& w = profile.weight;
    const auto problem = [](std::string field, std::string message) {
        return RecipeProblem{Severity::Error, std::move(field), std::move(message)};
    };
    if (z.size() != w.size())
        return problem("", std::to_string(z.size()) + " depths but " + std::to_string(w.size()) +
                               " weights; every node needs both");
    if (z.size() < 2) return problem("depth", "needs at least two nodes, at depth 0 and depth 1");
    for (std::size_t i = 0; i < z.size(); ++i)
        if (!std::isfinite(z[i])) return problem(nodeField("depth", i), "not a finite number");
    if (z.front() != 0.0)
        return problem(nodeField("depth", 0),
                       formatNumber(z.front()) + "; the first node must be at 0 (top of the layer)");
    if (z.back() != 1.0)
        return problem(nodeField("depth", z.size() - 1),
                       formatNumber(z.back()) + "; the last node must be at 1 (bottom of the layer)");
    for (std::size_t i = 1; i < z.size(); ++i)
        if (!(z[i] > z[i - 1]))
            return problem(nodeField("depth", i),
                           formatNumber(z[i]) + " is not below " + nodeField("depth", i - 1) + " (" +
                               formatNumber(z[i - 1]) + "); depth must increase strictly from 0 to 1");
    const ParameterDecl& decl = params::kProfileWeight;
    for (std::size_t i = 0; i < w.size(); ++i) {
        if (!std::isfinite(w[i])) return problem(nodeField("weight", i), "not a finite number");
        if (w[i] < decl.min)
            return problem(nodeField("weight", i), formatNumber(w[i]) + " is below 0; weights are >= 0");
        if (w[i] > decl.max)
            return problem(nodeField("weight", i),
                           formatNumber(w[i]) + " is above the maximum " + formatNumber(decl.max));
    }
    if (std::all_of(w.begin(), w.end(), [](double v) { return v == 0.0; }))
        return problem("weight", "all weights are zero; at least one node needs a positive weight");
    return problem("", "");
}

}  // namespace paintlab
