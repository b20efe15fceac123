// The glTF material fitted to a spectral BRDF (approx/material_fit.h).

#include "paintlab/engine/approx/material_fit.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe.h"

#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

namespace paintlab::approx {

namespace {

constexpr int kMainParameters = 9;  // base colour (3), metallic, roughness, specular, specular colour (3)
constexpr int kFilmParameters = 2;  // iridescence factor, thickness (nm)
constexpr double kMinRoughness = 0.03;
constexpr double kMaxSpecularColor = 10.0;  // f0 up to 0.4 at ior 1.5
constexpr double kMinThicknessNm = 100.0;
constexpr double kMaxThicknessNm = 1200.0;

struct Target {
    std::vector<std::pair<Direction, Direction>> pairs;
    std::vector<std::array<double, 3>> log_value;  // ln(1 + max(f, 0) cos_i) per channel
};

// The floor of the log residual, 1/sr (a reflectance factor of 0.03, L* 20):
// ln(1 + f cos) of the recipe fit hardly sees a dark flop (L* 5 and 30 differ
// by 0.05 in it), which is where a metallic's approximation goes wrong first.
constexpr double kLogFloor = 0.01;

double logValue(double f, double cos_i) { return std::log(kLogFloor + std::max(f, 0.0) * cos_i); }

GltfMaterial materialOf(const double* main, const double* film, const MaterialFitOptions& options) {
    GltfMaterial m;
    m.base_color = {main[0], main[1], main[2]};
    m.metallic = main[3];
    m.roughness = main[4];
    m.specular = main[5];
    m.specular_color = {main[6], main[7], main[8]};
    m.clearcoat = options.clearcoat;
    m.clearcoat_roughness = 0.0;
    m.iridescence_ior = options.iridescence_ior;
    if (options.iridescence) {
        m.iridescence = film[0];
        m.iridescence_thickness_nm = film[1];
    }
    return m;
}

struct Start {
    std::array<double, kMainParameters> main{};
    std::array<double, kFilmParameters> film{0.0, 400.0};
    double cost = std::numeric_limits<double>::infinity();
};

// The bounds of the main parameters, then of the film's.
constexpr std::array<double, kMainParameters + kFilmParameters> kLower{0, 0, 0, 0, kMinRoughness,  0,
                                                                       0, 0, 0, 0, kMinThicknessNm};
constexpr std::array<double, kMainParameters + kFilmParameters> kUpper{
    1, 1, 1, 1, 1, 1, kMaxSpecularColor, kMaxSpecularColor, kMaxSpecularColor, 1, kMaxThicknessNm};

// Bounds by a change of variable, x = lo + (hi - lo)(1 + sin u) / 2: the
// optimiser sees no bound and x never leaves [lo, hi].
double bounded(double u, std::size_t j) {
    return kLower[j] + (kUpper[j] - kLower[j]) * 0.5 * (1.0 + std::sin(u));
}
double unbounded(double x, std::size_t j) {
    const double t = 2.0 * (x - kLower[j]) / (kUpper[j] - kLower[j]) - 1.0;
    return std::asin(std::clamp(t, -1.0, 1.0));
}

// The residuals for Eigen's Levenberg-Marquardt (the functor interface of
// unsupported/Eigen/NonLinearOptimization).
struct LogResiduals {
    using Scalar = double;
    enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
    using InputType = Eigen::VectorXd;
    using ValueType = Eigen::VectorXd;
    using JacobianType = Eigen::MatrixXd;

    const Target* target = nullptr;
    MaterialFitOptions options;
    Start fixed;  // the film, when it is not fitted
    int free = kMainParameters;

    int inputs() const { return free; }
    int values() const { return static_cast<int>(3 * target->pairs.size()); }
    Start decode(const Eigen::VectorXd& u) const {
        Start s = fixed;
        for (std::size_t j = 0; j < static_cast<std::size_t>(free); ++j) {
            const double x = bounded(u[static_cast<Eigen::Index>(j)], j);
            if (j < kMainParameters)
                s.main[j] = x;
            else
                s.film[j - kMainParameters] = x;
        }
        return s;
    }
    int operator()(const Eigen::VectorXd& u, Eigen::VectorXd& residuals) const {
        const Start s = decode(u);
        const GltfMaterial m = materialOf(s.main.data(), s.film.data(), options);
        for (std::size_t k = 0; k < target->pairs.size(); ++k) {
            const auto& [wi, wo] = target->pairs[k];
            const Rgb f = evalGltf(m, wi, wo);
            const auto& t = target->log_value[k];
            const auto row = static_cast<Eigen::Index>(3 * k);
            residuals[row + 0] = logValue(f.r, wi.z) - t[0];
            residuals[row + 1] = logValue(f.g, wi.z) - t[1];
            residuals[row + 2] = logValue(f.b, wi.z) - t[2];
        }
        return 0;
    }
};

// One Levenberg-Marquardt solve from s (central differences); updates s.
void solve(const Target& target, const MaterialFitOptions& options, bool fit_film, Start& s) {
    LogResiduals functor{&target, options, s, fit_film ? kMainParameters + kFilmParameters : kMainParameters};
    Eigen::VectorXd u(functor.free);
    for (std::size_t j = 0; j < static_cast<std::size_t>(functor.free); ++j)
        u[static_cast<Eigen::Index>(j)] =
            unbounded(j < kMainParameters ? s.main[j] : s.film[j - kMainParameters], j);
    Eigen::NumericalDiff<LogResiduals, Eigen::Central> numeric(functor);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<LogResiduals, Eigen::Central>> lm(numeric);
    lm.parameters.maxfev = static_cast<Eigen::Index>(options.max_iterations) * (2 * functor.free + 1);
    lm.parameters.ftol = 1e-8;
    lm.parameters.xtol = 1e-8;
    lm.minimize(u);
    Eigen::VectorXd residuals(functor.values());
    functor(u, residuals);
    s = functor.decode(u);
    const double cost = 0.5 * residuals.squaredNorm();
    s.cost = std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

Target tabulate(const SpectralBrdf& brdf) {
    if (brdf.wavelengthsNm().size() < 2)
        throw InputError("<argument>", "brdf", "a BRDF with at least 2 wavelengths is needed for its colour");
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    Target t;
    t.pairs = gltfFitDirections();
    std::vector<double> spectrum(brdf.wavelengthsNm().size());
    for (const auto& [wi, wo] : t.pairs) {
        brdf.eval(wi, wo, spectrum);
        const Rgb f = weightedLinearSrgb(weights, spectrum);
        t.log_value.push_back({logValue(f.r, wi.z), logValue(f.g, wi.z), logValue(f.b, wi.z)});
    }
    return t;
}

}  // namespace

std::vector<std::pair<Direction, Direction>> gltfFitDirections() {
    std::vector<std::pair<Direction, Direction>> pairs;
    constexpr std::array<double, 6> kThetaDeg{5.0, 20.0, 35.0, 50.0, 65.0, 80.0};
    for (double theta_i : kThetaDeg)
        for (double theta_o : kThetaDeg)
            for (int k = 0; k <= 6; ++k)
                pairs.emplace_back(directionFromAnglesDeg(theta_i, 0.0),
                                   directionFromAnglesDeg(theta_o, 30.0 * k));
    for (int aspecular = -40; aspecular <= 130; aspecular += 5) {
        const MultiAngleGeometry g = multiAngleGeometry(aspecular);
        pairs.emplace_back(g.wi, g.wo);
    }
    return pairs;
}

std::vector<GeometryDeltaE>
multiAngleDeltaE(const SpectralBrdf& reference,
                 const std::function<Rgb(const Direction& wi, const Direction& wo)>& approximation) {
    // sRGB's conditions, so that the approximation's colour needs no adaptation.
    const MultiAngleReport report = multiAngleColours(reference, Illuminant::D65, Observer::Cie1931_2deg);
    const Xyz white = whitePoint(Illuminant::D65, Observer::Cie1931_2deg);
    std::vector<GeometryDeltaE> out;
    for (const MultiAngleColour& c : report.colours) {
        const MultiAngleGeometry g = multiAngleGeometry(c.aspecular_deg);
        const Rgb f = approximation(g.wi, g.wo);
        constexpr double kPi = std::numbers::pi;
        GeometryDeltaE d;
        d.aspecular_deg = c.aspecular_deg;
        d.reference = c.lab;
        d.approximation = xyzToLab(linearSrgbToXyz({kPi * f.r, kPi * f.g, kPi * f.b}), white);
        d.delta_e00 = ciede2000(d.reference, d.approximation);
        out.push_back(d);
    }
    return out;
}

MaterialFit fitGltfMaterial(const SpectralBrdf& brdf, const MaterialFitOptions& options) {
    const auto begin = std::chrono::steady_clock::now();
    const Target target = tabulate(brdf);
    // The starting colour: the reflectance factor seen along the normal (45as45).
    const MultiAngleGeometry normal = multiAngleGeometry(45.0);
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    const Rgb seen = weightedLinearSrgb(weights, brdf.eval(normal.wi, normal.wo));
    const auto startColour = [](double f) { return std::clamp(std::numbers::pi * f, 0.02, 0.98); };

    MaterialFit fit;
    Start best;
    // Two kinds of lobe from three widths: a metal's (coloured by the base
    // colour) and a dielectric's (coloured by the specular colour).
    struct Lobe {
        double metallic, specular, specular_color;
    };
    for (double roughness : {0.15, 0.35, 0.7})
        for (const Lobe lobe : {Lobe{0.6, 0.5, 1.0}, Lobe{0.02, 0.9, 5.0}}) {
            Start s;
            s.main = {startColour(seen.r), startColour(seen.g), startColour(seen.b),
                      lobe.metallic,       roughness,           lobe.specular,
                      lobe.specular_color, lobe.specular_color, lobe.specular_color};
            solve(target, options, false, s);
            ++fit.starts;
            if (s.cost < best.cost) best = s;
        }
    if (options.iridescence) {
        // The film's colour cycles with its thickness: a start every 100 nm.
        const Start plain = best;
        for (double thickness = 150.0; thickness <= 1050.0; thickness += 100.0) {
            Start s = plain;
            s.film = {0.8, thickness};
            solve(target, options, true, s);
            ++fit.starts;
            if (s.cost < best.cost) best = s;
        }
    }
    fit.material = materialOf(best.main.data(), best.film.data(), options);
    fit.rms_log_residual = std::sqrt(2.0 * best.cost / static_cast<double>(3 * target.pairs.size()));
    fit.geometries = multiAngleDeltaE(
        brdf, [&fit](const Direction& wi, const Direction& wo) { return evalGltf(fit.material, wi, wo); });
    for (const GeometryDeltaE& g : fit.geometries) {
        fit.max_delta_e00 = std::max(fit.max_delta_e00, g.delta_e00);
        fit.mean_delta_e00 += g.delta_e00 / static_cast<double>(fit.geometries.size());
    }
    fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return fit;
}

std::string deltaESummary(const MaterialFit& fit, std::string_view model) {
    // The maximum first: a status line cut at the window's edge keeps it.
    std::string line = std::string(model) + " approximation: max ΔE00 " +
                       io::formatFixed(fit.max_delta_e00, 2) + " against the fast model (";
    for (const GeometryDeltaE& g : fit.geometries)
        line.append("45as")
            .append(io::formatNumber(g.aspecular_deg))
            .append(" ")
            .append(io::formatFixed(g.delta_e00, 2))
            .append(", ");
    return line.append("fit ").append(io::formatFixed(fit.seconds, 2)).append(" s)");
}

MaterialFitOptions gltfFitOptions(const Recipe& recipe, const LayeredBrdf& brdf) {
    MaterialFitOptions options;
    for (const Layer& layer : recipe.layers)
        for (const Component& component : layer.components)
            if (const auto* flake = std::get_if<InterferenceFlake>(&component); flake != nullptr) {
                if (!options.iridescence) options.iridescence_ior = flake->tio2_refractive_index(550.0);
                options.iridescence = true;
            }
    // The clear coat's factor: its Schlick reflectance matched to the top
    // interface's mirror reflectance (luminance), least squares over mu.
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    const std::vector<double> ones(brdf.wavelengthsNm().size(), 1.0);
    const double white_y = weightedXyz(weights, ones).Y;
    double fr = 0.0;
    double ff = 0.0;
    for (int k = 1; k <= 20; ++k) {
        const double mu = 0.05 * k;
        const double y = weightedXyz(weights, brdf.specularReflectance(mu)).Y / white_y;
        const double m = 1.0 - mu;
        const double schlick = 0.04 + 0.96 * m * m * m * m * m;
        fr += schlick * y;
        ff += schlick * schlick;
    }
    options.clearcoat = std::clamp(fr / ff, 0.0, 1.0);
    return options;
}

MaterialFit fitGltfMaterial(const Recipe& recipe, const LayeredBrdf& brdf) {
    return fitGltfMaterial(brdf, gltfFitOptions(recipe, brdf));
}

}  // namespace paintlab::approx
