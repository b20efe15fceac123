#include "plot_data.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/fourier_series.h"
#include "paintlab/engine/fast_model/layered_brdf.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

namespace paintlab::gui {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

void checkIncidence(double theta_i_deg) {
    if (!(theta_i_deg >= 0.0 && theta_i_deg < 90.0))
        throw InputError("<argument>", "theta_i_deg",
                         "incidence " + std::to_string(theta_i_deg) + " deg is outside [0, 90)");
}

// The Fourier coefficients of every band at every (cos_o, cos_i) pair, per
// band (identity weights), so that each band can be summed and clipped at
// zero as LayeredBrdf::eval does. Index ((o * n_i + i) * orders + m) * bands + b.
std::vector<double> bandCoefficients(const LayeredBrdf& brdf, std::span<const double> cos_o,
                                     std::span<const double> cos_i) {
    const auto bands = static_cast<Eigen::Index>(brdf.wavelengthsNm().size());
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(bands, bands);
    std::vector<double> out(cos_o.size() * cos_i.size() * static_cast<std::size_t>(brdf.orders()) *
                            static_cast<std::size_t>(bands));
    brdf.fourierCoefficientsGrid(cos_o, cos_i, identity, out);
    return out;
}

// pi f per band at one (cos_o, cos_i) pair from its coefficients and cos(m dphi),
// summed and clipped at zero as LayeredBrdf::eval does.
void sumSeries(const double* coefficients, std::size_t orders, std::size_t bands,
               std::span<const double> cos_m_dphi, std::span<double> factor) {
    const std::span<const double> band_major(coefficients, orders * bands);
    for (std::size_t b = 0; b < bands; ++b)
        factor[b] =
            clippedFourierSum(cos_m_dphi.first(orders), band_major.subspan(b), bands, std::numbers::pi);
}

}  // namespace

InplaneSamples inplaneSamples(std::span<const measured::ScatteredSample> samples, double theta_i_deg,
                              double tolerance_deg) {
    InplaneSamples out;
    out.theta_i_deg = theta_i_deg;
    out.tolerance_deg = tolerance_deg;
    out.total = samples.size();
    const double sin_tolerance = std::sin(tolerance_deg * kDeg);
    for (const measured::ScatteredSample& s : samples) {
        const double wi_len = std::sqrt(s.wi.x * s.wi.x + s.wi.y * s.wi.y + s.wi.z * s.wi.z);
        const double wo_len = std::sqrt(s.wo.x * s.wo.x + s.wo.y * s.wo.y + s.wo.z * s.wo.z);
        const double sample_theta_i = std::acos(std::clamp(s.wi.z / wi_len, -1.0, 1.0)) / kDeg;
        if (std::abs(sample_theta_i - theta_i_deg) > tolerance_deg || s.values.size() < 3) continue;
        // u: in the surface, away from the light (towards the mirror
        // direction); the plane of incidence is spanned by u and the normal.
        const double h = std::hypot(s.wi.x, s.wi.y);
        const double ux = h > 1e-9 ? -s.wi.x / h : 1.0;
        const double uy = h > 1e-9 ? -s.wi.y / h : 0.0;
        const double off_plane = (-uy * s.wo.x + ux * s.wo.y) / wo_len;  // sine of the angle to the plane
        if (std::abs(off_plane) > sin_tolerance) continue;
        out.view_deg.push_back(std::atan2(ux * s.wo.x + uy * s.wo.y, s.wo.z) / kDeg);
        out.r.push_back(std::numbers::pi * s.values[0]);
        out.g.push_back(std::numbers::pi * s.values[1]);
        out.b.push_back(std::numbers::pi * s.values[2]);
    }
    return out;
}

std::vector<double> inplaneViewAnglesDeg() {
    std::vector<double> view;
    for (int k = 0; k <= 68; ++k) view.push_back(-85.0 + 2.5 * k);
    return view;
}

std::vector<InplaneCurve> inplaneCurves(const LayeredBrdf& brdf, std::span<const double> incidences_deg) {
    for (double theta_i : incidences_deg) checkIncidence(theta_i);
    const std::vector<double> view = inplaneViewAnglesDeg();
    // The view angles come in +-pairs with the same polar angle: one cosine each.
    std::vector<double> polar_deg;
    for (double v : view)
        if (v >= 0.0) polar_deg.push_back(v);
    std::vector<double> cos_o;
    cos_o.reserve(polar_deg.size());
    for (double p : polar_deg) cos_o.push_back(std::cos(p * kDeg));
    std::vector<double> cos_i;
    cos_i.reserve(incidences_deg.size());
    for (double t : incidences_deg) cos_i.push_back(std::cos(t * kDeg));
    const std::vector<double> coefficients = bandCoefficients(brdf, cos_o, cos_i);

    const std::size_t bands = brdf.wavelengthsNm().size();
    const auto orders = static_cast<std::size_t>(brdf.orders());
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    // The light is at azimuth 180: the light's side has dphi = 0, the far side dphi = 180.
    std::vector<double> same_side(orders, 1.0);
    std::vector<double> far_side(orders);
    for (std::size_t m = 0; m < orders; ++m) far_side[m] = m % 2 == 0 ? 1.0 : -1.0;
    std::vector<double> factor(bands);
    std::vector<InplaneCurve> curves;
    for (std::size_t i = 0; i < cos_i.size(); ++i) {
        InplaneCurve c;
        c.theta_i_deg = incidences_deg[i];
        for (double v : view) {
            const auto o = static_cast<std::size_t>(
                std::find(polar_deg.begin(), polar_deg.end(), std::abs(v)) - polar_deg.begin());
            sumSeries(coefficients.data() + (o * cos_i.size() + i) * orders * bands, orders, bands,
                      v >= 0.0 ? far_side : same_side, factor);
            const Rgb rgb = weightedLinearSrgb(weights, factor);
            c.view_deg.push_back(v);
            c.r.push_back(rgb.r);
            c.g.push_back(rgb.g);
            c.b.push_back(rgb.b);
            c.y.push_back(weightedXyz(weights, factor).Y);
        }
        curves.push_back(std::move(c));
    }
    return curves;
}

LobeGrid lobeGrid(const LayeredBrdf& brdf, double theta_i_deg, double phi_i_deg, int theta_count,
                  int phi_count, double max_theta_deg) {
    const auto start = std::chrono::steady_clock::now();
    checkIncidence(theta_i_deg);
    if (theta_count < 2 || phi_count < 2)
        throw InputError("<argument>", "theta_count", "a lobe grid needs at least 2 rings and 2 azimuths");
    LobeGrid g;
    g.theta_i_deg = theta_i_deg;
    g.phi_i_deg = phi_i_deg;
    std::vector<double> cos_o;
    for (int t = 0; t < theta_count; ++t) {
        g.theta_o_deg.push_back(max_theta_deg * t / (theta_count - 1));
        cos_o.push_back(std::cos(g.theta_o_deg.back() * kDeg));
    }
    for (int p = 0; p < phi_count; ++p) g.phi_o_deg.push_back(360.0 * p / phi_count);
    const std::vector<double> cos_i{std::cos(theta_i_deg * kDeg)};
    const std::vector<double> coefficients = bandCoefficients(brdf, cos_o, cos_i);

    const std::size_t bands = brdf.wavelengthsNm().size();
    const auto orders = static_cast<std::size_t>(brdf.orders());
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    // cos(m (phi_o - phi_i)) per azimuth and order.
    std::vector<double> cos_m(static_cast<std::size_t>(phi_count) * orders);
    for (std::size_t p = 0; p < g.phi_o_deg.size(); ++p)
        for (std::size_t m = 0; m < orders; ++m)
            cos_m[p * orders + m] = std::cos(static_cast<double>(m) * (g.phi_o_deg[p] - phi_i_deg) * kDeg);
    std::vector<double> factor(bands);
    g.y.reserve(cos_o.size() * g.phi_o_deg.size());
    g.linear_srgb.reserve(g.y.capacity());
    for (std::size_t o = 0; o < cos_o.size(); ++o) {
        for (std::size_t p = 0; p < g.phi_o_deg.size(); ++p) {
            sumSeries(coefficients.data() + o * orders * bands, orders, bands,
                      std::span<const double>(cos_m).subspan(p * orders, orders), factor);
            g.y.push_back(weightedXyz(weights, factor).Y);
            g.linear_srgb.push_back(weightedLinearSrgb(weights, factor));
            g.max_y = std::max(g.max_y, g.y.back());
        }
    }
    g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return g;
}

std::string geometryName(double aspecular_deg) {
    const long rounded = std::lround(aspecular_deg);
    return "45as" + std::to_string(rounded);
}

std::vector<NamedSpectrum> multiAngleSpectra(const MultiAngleReport& report,
                                             std::span<const double> wavelengths_nm) {
    std::vector<NamedSpectrum> out;
    for (const MultiAngleColour& c : report.colours)
        out.push_back({geometryName(c.aspecular_deg), "Reflectance factor (1)",
                       Spectrum(std::vector<double>(wavelengths_nm.begin(), wavelengths_nm.end()),
                                c.reflectance_factor)});
    return out;
}

namespace {

// The quantity a spectral field is of: fields that share an axis (every
// refractive index, every coefficient in 1/µm) are grouped; ordered so that
// the absorption and scattering of the colorants come first.
struct Quantity {
    int rank = 0;
    std::string name;
};

Quantity quantityOf(const ParameterDecl& decl) {
    using namespace params;
    if (&decl == &kPigmentSigmaA || &decl == &kPigmentSigmaS || &decl == &kBinderAbsorption)
        return {0, "Absorption and scattering coefficients (1/µm)"};
    if (&decl == &kMirrorReflectance || &decl == &kRawAlbedo || &decl == &kSubstrateAlbedo)
        return {1, "Reflectance and albedo (1)"};
    if (&decl == &kBinderIndex || &decl == &kMicaIndex || &decl == &kTio2Index || &decl == &kMetalN)
        return {2, "Refractive index n (1)"};
    if (&decl == &kMetalK) return {3, "Extinction coefficient k (1)"};
    return {4, std::string(decl.label) + " (" + std::string(decl.unit) + ")"};
}

// Collects the spectral fields of one struct through its traversal hook.
struct SpectrumCollector {
    std::string prefix;
    std::vector<std::pair<int, NamedSpectrum>>* out = nullptr;

    void scalar(const ParameterDecl& /*decl*/, const double& /*value*/) {}
    void spectrum(const ParameterDecl& decl, const Spectrum& value) {
        Quantity q = quantityOf(decl);
        out->push_back({q.rank, {prefix + std::string(decl.label), std::move(q.name), value}});
    }
    void optionalSpectrum(const ParameterDecl& decl, const std::optional<Spectrum>& value) {
        if (value) spectrum(decl, *value);
    }
};

}  // namespace

std::vector<NamedSpectrum> recipeSpectra(const Recipe& recipe) {
    std::vector<std::pair<int, NamedSpectrum>> out;
    // Components before binders: within a quantity, the colorants come first.
    for (const Layer& layer : recipe.layers) {
        for (const Component& component : layer.components) {
            std::visit(
                [&](const auto& c) {
                    using T = std::remove_cv_t<std::remove_reference_t<decltype(c)>>;
                    SpectrumCollector v{layer.name + " > " + c.name + " > ", &out};
                    T::traverse(c, v);
                },
                component);
        }
    }
    for (const Layer& layer : recipe.layers) {
        SpectrumCollector binder{layer.name + " > " + layer.binder.name + " > ", &out};
        Binder::traverse(layer.binder, binder);
    }
    std::visit(
        [&](const auto& s) {
            using T = std::remove_cv_t<std::remove_reference_t<decltype(s)>>;
            SpectrumCollector v{"substrate (" + std::string(T::kKind) + ") > ", &out};
            T::traverse(s, v);
        },
        recipe.substrate);
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<NamedSpectrum> spectra;
    spectra.reserve(out.size());
    for (auto& [rank, s] : out) spectra.push_back(std::move(s));
    return spectra;
}

Rgb8 displayColour(const Rgb& linear_srgb) {
    const double r = std::max(0.0, linear_srgb.r);
    const double g = std::max(0.0, linear_srgb.g);
    const double b = std::max(0.0, linear_srgb.b);
    const double peak = std::max({r, g, b});
    if (!(peak > 0.0)) return {};
    const auto channel = [peak](double v) {
        return static_cast<unsigned char>(std::lround(255.0 * std::clamp(srgbEncode(v / peak), 0.0, 1.0)));
    };
    return {channel(r), channel(g), channel(b)};
}

}  // namespace paintlab::gui
