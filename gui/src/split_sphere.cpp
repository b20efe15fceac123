// The split sphere of a match (split_sphere.h).

#include "split_sphere.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/raymaps/relight.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>

namespace paintlab::gui {

namespace {

Direction unit(double x, double y, double z) {
    const double n = std::sqrt(x * x + y * y + z * z);
    return {x / n, y / n, z / n};
}

double dot(const Direction& a, const Direction& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The pixel's normal and a tangent frame around it (isotropic BRDFs: any one).
struct Frame {
    Direction t, b, n;
    Direction local(const Direction& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
};

Frame frameAt(const Direction& n) {
    // t = (0, 1, 0) x n, or the x axis where n is (nearly) the y axis.
    Direction t{n.z, 0.0, -n.x};
    const double len = std::sqrt(t.x * t.x + t.z * t.z);
    t = len > 1e-6 ? Direction{t.x / len, 0.0, t.z / len} : Direction{1.0, 0.0, 0.0};
    const Direction b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
    return {t, b, n};
}

// The sphere's normal at pixel (px, py), or nothing outside the disc.
bool normalAt(int px, int py, int size, Direction& n) {
    const double x = 2.0 * (px + 0.5) / size - 1.0;
    const double y = 1.0 - 2.0 * (py + 0.5) / size;
    const double r2 = x * x + y * y;
    if (r2 >= 1.0) return false;
    n = {x, y, std::sqrt(1.0 - r2)};
    return true;
}

constexpr Direction kView{0.0, 0.0, 1.0};

}  // namespace

std::vector<measured::ScatteredSample> linearSrgbSamples(const db::Measurement& m) {
    const std::string source = "measurement '" + m.name + "'";
    if (m.kind != db::MeasurementKind::Brdf)
        throw InputError(source, "kind", "has no BRDF samples (it is a multi-angle reading)");
    std::array<std::size_t, 3> rgb_index{};
    std::optional<BandColourWeights> weights;
    if (!m.channels.empty()) {
        for (std::size_t c = 0; c < 3; ++c) {
            const char* name = c == 0 ? "R" : c == 1 ? "G" : "B";
            const auto at = std::find(m.channels.begin(), m.channels.end(), name);
            if (at == m.channels.end() || m.channels.size() != 3)
                throw InputError(source, "channels", "linear sRGB needs exactly the channels R, G and B");
            rgb_index[c] = static_cast<std::size_t>(at - m.channels.begin());
        }
    } else {
        if (m.wavelengths_nm.size() < 2)
            throw InputError(source, "wavelengths_nm", "a spectral BRDF needs at least 2 wavelengths");
        weights = bandColourWeights(m.wavelengths_nm);
    }
    std::vector<measured::ScatteredSample> out;
    out.reserve(m.samples.size());
    for (const db::BrdfSample& s : m.samples) {
        measured::ScatteredSample sample{directionFromAnglesDeg(s.theta_i_deg, s.phi_i_deg),
                                         directionFromAnglesDeg(s.theta_o_deg, s.phi_o_deg),
                                         {}};
        if (weights) {
            // Negative sRGB channels are colours outside the gamut: at 0, as displayed.
            const Rgb c = weightedLinearSrgb(*weights, s.values);
            sample.values = {std::max(c.r, 0.0), std::max(c.g, 0.0), std::max(c.b, 0.0)};
        } else {
            for (std::size_t c = 0; c < 3; ++c) sample.values.push_back(s.values.at(rgb_index[c]));
        }
        out.push_back(std::move(sample));
    }
    return out;
}

std::span<const SphereLight> splitSphereLights() {
    // Key (upper left, in front), fill (right), and a dim light from the
    // camera for the environment; irradiance in units of pi so a white
    // diffuser facing the key light shows 0.8.
    static const std::array<SphereLight, 3> kLights{{
        {unit(-0.45, 0.55, 0.70), 0.8 * std::numbers::pi},
        {unit(0.75, -0.10, 0.65), 0.25 * std::numbers::pi},
        {kView, 0.10 * std::numbers::pi},
    }};
    return kLights;
}

std::vector<measured::DirectionPair> splitSphereQueries(int size_px) {
    std::vector<measured::DirectionPair> out;
    for (int py = 0; py < size_px; ++py)
        for (int px = 0; px < size_px / 2; ++px) {
            Direction n;
            if (!normalAt(px, py, size_px, n)) continue;
            const Frame f = frameAt(n);
            for (const SphereLight& light : splitSphereLights())
                if (dot(light.towards, n) > 0.0) out.push_back({f.local(light.towards), f.local(kView)});
        }
    return out;
}

RgbBrdf rgbBrdf(const measured::ScatteredBrdf& brdf) {
    return [&brdf](const Direction& wi, const Direction& wo) {
        std::array<double, 3> f{};
        brdf.eval(wi, wo, f);
        return Rgb{f[0], f[1], f[2]};
    };
}

RgbBrdf rgbBrdf(const LayeredBrdf& brdf) {
    // The render dock's own reduction (raymaps RelightTables: the BRDF in
    // linear sRGB on a 33 x 33 x 65 grid, read as its explicit lights read
    // it): the fitted half looks as the recipe does in the render, and a
    // lookup costs a trilinear read instead of an eval() over every band
    // (measured: the sphere took 8 s with eval(), see gui/README.md).
    auto tables = std::make_shared<const raymaps::RelightTables>(brdf, 1, 1);
    return [tables](const Direction& wi, const Direction& wo) {
        if (!(wi.z > 0.0) || !(wo.z > 0.0)) return Rgb{};
        const double ti = std::hypot(wi.x, wi.y);
        const double to = std::hypot(wo.x, wo.y);
        const double cos_dphi = ti > 1e-9 && to > 1e-9 ? (wi.x * wo.x + wi.y * wo.y) / (ti * to) : 1.0;
        const raymaps::Rgb3 f = tables->lightTable(wo.z, wi.z, cos_dphi);
        return Rgb{f.x(), f.y(), f.z()};
    };
}

raymaps::RgbImage renderSplitSphere(const RgbBrdf& left, const RgbBrdf& right, int size_px,
                                    const std::function<bool()>& alive) {
    if (size_px < 8)
        throw InputError("<argument>", "size_px", std::to_string(size_px) + " pixels: at least 8");
    const auto side = static_cast<std::size_t>(size_px);
    raymaps::RgbImage image{size_px, size_px, std::vector<float>(3 * side * side, 0.0F)};
    std::atomic<bool> cancelled{false};
    tbb::parallel_for(0, size_px, [&](int py) {
        if (cancelled.load(std::memory_order_relaxed)) return;
        if (alive && !alive()) {
            cancelled = true;
            return;
        }
        for (int px = 0; px < size_px; ++px) {
            Direction n;
            if (!normalAt(px, py, size_px, n)) continue;
            const Frame frame = frameAt(n);
            const RgbBrdf& brdf = px < size_px / 2 ? left : right;
            const Direction wo = frame.local(kView);
            Rgb radiance;
            for (const SphereLight& light : splitSphereLights()) {
                const double cos_i = dot(light.towards, n);
                if (cos_i <= 0.0) continue;
                const Rgb f = brdf(frame.local(light.towards), wo);
                const double e = light.irradiance * cos_i;
                radiance.r += e * f.r;
                radiance.g += e * f.g;
                radiance.b += e * f.b;
            }
            float* out = &image.rgb[3 * (static_cast<std::size_t>(py) * side + static_cast<std::size_t>(px))];
            out[0] = static_cast<float>(radiance.r);
            out[1] = static_cast<float>(radiance.g);
            out[2] = static_cast<float>(radiance.b);
        }
    });
    if (cancelled) throw Error("cancelled");
    return image;
}

double splitSphereExposureEv(const raymaps::RgbImage& image) {
    std::vector<float> peaks;
    for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
        const float m = std::max({image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]});
        if (m > 0.0F) peaks.push_back(m);
    }
    if (peaks.empty()) return 0.0;
    const auto at = peaks.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(peaks.size() - 1));
    std::nth_element(peaks.begin(), at, peaks.end());
    return std::clamp(-std::log2(static_cast<double>(*at)), -10.0, 10.0);
}

}  // namespace paintlab::gui
