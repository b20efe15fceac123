// Relight: the recipe's tables (cost independent of the image) and the pass
// over the paint records (docs/RAYMAPS.md, "Relight").

#include "record_layout.h"
#include "sampling.h"

#include "paintlab/engine/brdf_colour.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/layered_brdf.h"
#include "paintlab/raymaps/relight.h"

#include <Imath/half.h>
#include <tbb/parallel_for.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

namespace paintlab::raymaps {

namespace {

constexpr int kN = RelightTables::kMuNodes;
constexpr int kC = RelightTables::kPhiNodes;

// 8-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 8> kGaussX{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                        -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                        0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGaussW{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                        0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                        0.2223810344533745, 0.1012285362903763};

// arccos to 7e-5 rad without a library call (Abramowitz and Stegun 4.4.45).
inline float fastAcos(float x) {
    const float ax = std::min(std::abs(x), 1.0F);
    const float r =
        std::sqrt(1.0F - ax) * (1.5707288F + ax * (-0.2121144F + ax * (0.0742610F - 0.0187293F * ax)));
    return x >= 0.0F ? r : static_cast<float>(kPi) - r;
}

// The grid is uniform in the polar angle: the odd Fourier orders of f go as
// sin(theta) near the normal, which no grid in mu = cos(theta) follows. At
// the horizon eval() is 0 by definition, so that node takes mu = 0.002.
// i * n + m in size_t.
std::size_t index2(int i, int n, int m) {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(m);
}

double muNode(int k) { return std::max(0.002, std::cos(0.5 * kPi * k / (kN - 1))); }

// Continuous index on the theta grid, clamped to its ends.
inline void muIndex(float mu, int& k, float& t) {
    const float x = std::clamp(fastAcos(mu) * static_cast<float>((kN - 1) / (0.5 * kPi)), 0.0F,
                               static_cast<float>(kN - 1) - 1e-4F);
    k = static_cast<int>(x);
    t = x - static_cast<float>(k);
}

float halfToFloat(std::uint16_t bits) {
    Imath::half h;
    h.setBits(bits);
    return static_cast<float>(h);
}

// The nearest fine-grid node of a position (k, t) on the coarse theta grid.
// The position is never negative, so adding 1/2 and truncating rounds to
// nearest (without lround's library call in the kernel).
inline std::size_t fineIndex(int k, float t) {
    constexpr float kRatio = static_cast<float>(RelightTables::kFineNodes - 1) / static_cast<float>(kN - 1);
    const float x = (static_cast<float>(k) + t) * kRatio + 0.5F;
    return static_cast<std::size_t>(x);  // NOLINT(bugprone-incorrect-roundings)
}

template <typename T> T get(const std::byte* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

}  // namespace

RelightTables::RelightTables(const LayeredBrdf& brdf, int cells, int orders)
    : m_cells(cells), m_orders(orders) {
    if (cells < 1 || cells > 16 || orders < 1 || orders > 16)
        throw InputError("<argument>", "cells/orders", "J must be in [1, 16] and M_L in [1, 16]");
    const auto start = std::chrono::steady_clock::now();
    const auto wavelengths = brdf.wavelengthsNm();
    const std::size_t bands = wavelengths.size();
    // Linear sRGB is linear in the spectrum: the weights are the colours of
    // the unit spectra (brdf_colour.h: D65 / 2 degrees, white -> (1, 1, 1)).
    m_weights.assign(3 * bands, 0.0);
    std::vector<double> unit(bands, 0.0);
    for (std::size_t b = 0; b < bands; ++b) {
        unit[b] = 1.0;
        const Rgb c = spectrumColour(wavelengths, unit).linear_srgb;
        unit[b] = 0.0;
        m_weights[3 * b] = c.r;
        m_weights[3 * b + 1] = c.g;
        m_weights[3 * b + 2] = c.b;
    }
    // Orders kept: at least 8 (the light table sums them at kC azimuths).
    const int n_phi = std::max(8, brdf.settings().orders);
    const auto nu = static_cast<std::size_t>(kN);
    m_light.assign(nu * nu * static_cast<std::size_t>(kC) * 3, 0.0F);
    const std::size_t per_node = static_cast<std::size_t>(cells) * static_cast<std::size_t>(orders) * 3;
    std::vector<float> moments(nu * per_node, 0.0F);
    std::vector<float> coats(nu * 3, 0.0F);

    tbb::parallel_for(0, kN, [&](int o) {
        const double mu_o = muNode(o);
        std::vector<double> spectrum(bands);
        std::vector<Rgb3> a(static_cast<std::size_t>(n_phi));
        std::vector<Rgb3> node_a(static_cast<std::size_t>(kN * orders),
                                 Rgb3::Zero());  // a_m at the theta_i nodes
        // Fourier cosine coefficients of f_rgb(mu_o, mu_i, phi): f = sum_m a_m
        // cos(m phi), straight from the fast model's tables (one product per
        // order and band; sampling eval() over phi cost 9x more).
        std::vector<double> series(static_cast<std::size_t>(brdf.orders()) * bands);
        const auto coefficients = [&](double mu_i) {
            brdf.fourierCoefficients(mu_o, mu_i, series);
            for (int m = 0; m < n_phi; ++m) {
                const auto mm = static_cast<std::size_t>(m);
                if (m >= brdf.orders()) {
                    a[mm] = Rgb3::Zero();
                    continue;
                }
                std::copy_n(series.begin() + static_cast<std::ptrdiff_t>(mm * bands), bands,
                            spectrum.begin());
                a[mm] = toRgb(spectrum);
            }
        };
        for (int i = 0; i < kN; ++i) {
            coefficients(muNode(i));
            for (int m = 0; m < orders && m < n_phi; ++m)
                node_a[index2(i, orders, m)] = a[static_cast<std::size_t>(m)];
            for (int c = 0; c < kC; ++c) {
                const double dphi = kPi * c / (kC - 1);
                Rgb3 value = Rgb3::Zero();
                for (int m = 0; m < n_phi; ++m) value += a[static_cast<std::size_t>(m)] * std::cos(m * dphi);
                for (int ch = 0; ch < 3; ++ch)
                    m_light[((static_cast<std::size_t>(o) * nu + static_cast<std::size_t>(i)) * kC +
                             static_cast<std::size_t>(c)) *
                                3 +
                            static_cast<std::size_t>(ch)] = static_cast<float>(std::max(0.0, value[ch]));
            }
        }
        // Cell averages weighted by mu (the moments are integrals over mu dmu):
        // fbar^m_j = int_cell a_m mu dmu / int_cell mu dmu, int_cell mu dmu = 1 / (2 J).
        for (int j = 0; j < cells; ++j) {
            const double lo = std::sqrt(static_cast<double>(j) / cells);
            const double hi = std::sqrt(static_cast<double>(j + 1) / cells);
            std::vector<Rgb3> sum(static_cast<std::size_t>(orders), Rgb3::Zero());
            // In theta: int a_m mu dmu = int a_m cos sin dtheta, a_m linear
            // between the theta_i nodes (no further eval() call: this is
            // where the tables' time would go); 4 x 8 Gauss points per cell.
            const double theta_lo = std::acos(hi);
            const double theta_hi = std::acos(lo);
            constexpr int kPieces = 4;
            for (int piece = 0; piece < kPieces; ++piece) {
                const double a0 = theta_lo + (theta_hi - theta_lo) * piece / kPieces;
                const double a1 = theta_lo + (theta_hi - theta_lo) * (piece + 1) / kPieces;
                for (std::size_t g = 0; g < kGaussX.size(); ++g) {
                    const double theta = 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * kGaussX[g];
                    const double x = std::clamp(theta / (0.5 * kPi) * (kN - 1), 0.0, kN - 1 - 1e-9);
                    const int k = static_cast<int>(x);
                    const double t = x - k;
                    const double w = 0.5 * (a1 - a0) * kGaussW[g] * std::cos(theta) * std::sin(theta);
                    for (int m = 0; m < orders; ++m)
                        sum[static_cast<std::size_t>(m)] += w * ((1.0 - t) * node_a[index2(k, orders, m)] +
                                                                 t * node_a[index2(k + 1, orders, m)]);
                }
            }
            for (int m = 0; m < orders; ++m)
                for (int ch = 0; ch < 3; ++ch)
                    moments[((static_cast<std::size_t>(o) * static_cast<std::size_t>(cells) +
                              static_cast<std::size_t>(j)) *
                                 static_cast<std::size_t>(orders) +
                             static_cast<std::size_t>(m)) *
                                3 +
                            static_cast<std::size_t>(ch)] =
                        static_cast<float>(sum[static_cast<std::size_t>(m)][ch] * 2.0 * cells);
        }
        const Rgb3 coat = toRgb(brdf.specularReflectance(mu_o));
        for (int ch = 0; ch < 3; ++ch)
            coats[3 * static_cast<std::size_t>(o) + static_cast<std::size_t>(ch)] =
                static_cast<float>(coat[ch]);
    });
    // Resampled on the fine grid (see kFineNodes), m >= 1 scaled by 1/127.
    constexpr int kF = kFineNodes;
    m_moments.assign(static_cast<std::size_t>(kF) * per_node, 0.0F);
    m_coat.assign(static_cast<std::size_t>(kF) * 3, 0.0F);
    for (int f = 0; f < kF; ++f) {
        const double x = std::min(static_cast<double>(f) * (kN - 1) / (kF - 1), kN - 1 - 1e-9);
        const auto k = static_cast<std::size_t>(x);
        const auto t = static_cast<float>(x - static_cast<double>(k));
        const auto uf = static_cast<std::size_t>(f);
        for (std::size_t e = 0; e < per_node; ++e) {
            const bool first_order = (e / 3) % static_cast<std::size_t>(orders) == 0;
            m_moments[uf * per_node + e] =
                ((1.0F - t) * moments[k * per_node + e] + t * moments[(k + 1) * per_node + e]) *
                (first_order ? 1.0F : 1.0F / 127.0F);
        }
        for (std::size_t c = 0; c < 3; ++c)
            m_coat[uf * 3 + c] = (1.0F - t) * coats[k * 3 + c] + t * coats[(k + 1) * 3 + c];
    }
    m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Rgb3 RelightTables::toRgb(const std::vector<double>& spectrum) const {
    Rgb3 c = Rgb3::Zero();
    for (std::size_t b = 0; b < spectrum.size() && 3 * b + 2 < m_weights.size(); ++b)
        c += spectrum[b] * Rgb3(m_weights[3 * b], m_weights[3 * b + 1], m_weights[3 * b + 2]);
    return c;
}

namespace {

// Trilinear lookup in the light table (the kernel's, in float).
inline Eigen::Vector3f lookupLight(const float* table, int ko, float to, float mu_i, float cos_dphi) {
    int ki = 0;
    float ti = 0.0F;
    muIndex(mu_i, ki, ti);
    const float xc = std::clamp(fastAcos(cos_dphi) * static_cast<float>((kC - 1) / kPi), 0.0F,
                                static_cast<float>(kC - 1) - 1e-4F);
    const int kc = static_cast<int>(xc);
    const float tc = xc - static_cast<float>(kc);
    Eigen::Vector3f out = Eigen::Vector3f::Zero();
    for (int dox = 0; dox < 2; ++dox)
        for (int dix = 0; dix < 2; ++dix)
            for (int dcx = 0; dcx < 2; ++dcx) {
                const float w =
                    (dox != 0 ? to : 1.0F - to) * (dix != 0 ? ti : 1.0F - ti) * (dcx != 0 ? tc : 1.0F - tc);
                const float* e =
                    table +
                    ((static_cast<std::size_t>(ko + dox) * kN + static_cast<std::size_t>(ki + dix)) * kC +
                     static_cast<std::size_t>(kc + dcx)) *
                        3;
                out += w * Eigen::Vector3f(e[0], e[1], e[2]);
            }
    return out;
}

}  // namespace

Rgb3 RelightTables::lightTable(double mu_o, double mu_i, double cos_dphi) const {
    int ko = 0;
    float to = 0.0F;
    muIndex(static_cast<float>(mu_o), ko, to);
    return lookupLight(m_light.data(), ko, to, static_cast<float>(mu_i), static_cast<float>(cos_dphi))
        .cast<double>();
}

Rgb3 RelightTables::coat(double mu_o) const {
    int k = 0;
    float t = 0.0F;
    muIndex(static_cast<float>(std::clamp(mu_o, 0.0, 1.0)), k, t);
    const std::size_t f = 3 * fineIndex(k, t);
    return Eigen::Vector3f(m_coat[f], m_coat[f + 1], m_coat[f + 2]).cast<double>();
}

RgbImage relight(const RayMap& map, const RelightTables& tables) {
    const RayMapHeader& h = map.header();
    if (h.cells != tables.cells() || h.orders != tables.orders())
        throw InputError(map.path().string(), "header",
                         "the map has J = " + std::to_string(h.cells) +
                             ", M_L = " + std::to_string(h.orders) +
                             "; the relight tables were built for J = " + std::to_string(tables.cells()) +
                             ", M_L = " + std::to_string(tables.orders()));
    RgbImage image;
    image.width = h.width;
    image.height = h.height;
    image.rgb.assign(static_cast<std::size_t>(h.width) * static_cast<std::size_t>(h.height) * 3, 0.0F);
    const RecordLayout layout{h.cells, h.orders, static_cast<int>(h.lights.size())};
    const std::size_t stride = layout.bytes();
    const auto cells = static_cast<std::size_t>(h.cells);
    const auto orders = static_cast<std::size_t>(h.orders);
    const float* light_table = tables.light().data();
    const float* moments = tables.moments().data();
    const float* coat = tables.coat().data();
    const std::size_t moment_stride = cells * orders * 3;  // per mu_o node
    struct KernelLight {
        bool point;
        Eigen::Vector3f vector;
        Eigen::Vector3f power;
    };
    std::vector<KernelLight> lights;
    for (const ExplicitLight& l : h.lights)
        lights.push_back(
            {l.kind == ExplicitLight::Kind::Point, l.vector.cast<float>(), l.power.cast<float>()});

    tbb::parallel_for(0, map.bandCount(), [&](int b) {
        const RayMapBand& band = map.band(b);
        float* out = image.rgb.data() +
                     static_cast<std::size_t>(band.first_row) * static_cast<std::size_t>(h.width) * 3;
        for (std::size_t i = 0; i < band.baked.size(); ++i) out[i] = halfToFloat(band.baked[i]);
        float* image_base = image.rgb.data();
        // Records in ascending pixel order; a parallel loop inside the band
        // keeps both cores busy when the paint sits in a few bands.
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, band.record_count, 256),
            [&](const tbb::blocked_range<std::size_t>& range) {
                for (std::size_t r = range.begin(); r != range.end(); ++r) {
                    const std::byte* rec = band.records.data() + r * stride;
                    const auto pixel = get<std::uint32_t>(rec + RecordLayout::kPixel);
                    const Eigen::Vector3f n =
                        decodeOctahedral(get<std::uint16_t>(rec + RecordLayout::kNormal),
                                         get<std::uint16_t>(rec + RecordLayout::kNormal + 2));
                    const Eigen::Vector3f v =
                        decodeOctahedral(get<std::uint16_t>(rec + RecordLayout::kView),
                                         get<std::uint16_t>(rec + RecordLayout::kView + 2));
                    const float mu_o = std::clamp(n.dot(v), 0.0F, 1.0F);
                    Eigen::Vector3f t = v - mu_o * n;
                    const float t_len = t.norm();
                    // Seen along the normal the BRDF does not depend on the azimuth: any tangent does.
                    t = t_len > 1e-6F ? Eigen::Vector3f(t / t_len) : Eigen::Vector3f::Zero();
                    int ko = 0;
                    float to = 0.0F;
                    muIndex(mu_o, ko, to);
                    Eigen::Vector3f l = Eigen::Vector3f::Zero();
                    // Incident-light moments: sum_j sum_m fbar^m(mu_o, j) l^m_j,
                    // the table at the nearest fine theta_o node.
                    const float* mt = moments + fineIndex(ko, to) * moment_stride;
                    const auto* q = reinterpret_cast<const std::int8_t*>(rec + layout.momentsM());
                    for (std::size_t j = 0; j < cells; ++j) {
                        for (std::size_t c = 0; c < 3; ++c) {
                            const float l0 = halfToFloat(
                                get<std::uint16_t>(rec + RecordLayout::kMoments0 + 6 * j + 2 * c));
                            const float* row = mt + j * orders * 3 + c;
                            float sum = row[0];
                            for (std::size_t m = 1; m < orders; ++m)
                                sum +=
                                    row[3 * m] * static_cast<float>(q[3 * ((orders - 1) * j + (m - 1)) + c]);
                            l[static_cast<Eigen::Index>(c)] += sum * l0;
                        }
                    }
                    // Explicit lights: V f(wi, wo) E cos(theta_i).
                    const Eigen::Vector3f position(get<float>(rec + RecordLayout::kPosition),
                                                   get<float>(rec + RecordLayout::kPosition + 4),
                                                   get<float>(rec + RecordLayout::kPosition + 8));
                    for (std::size_t k = 0; k < lights.size(); ++k) {
                        const auto vis = get<std::uint8_t>(rec + layout.visibility() + k);
                        if (vis == 0) continue;
                        Eigen::Vector3f wi = lights[k].vector;
                        Eigen::Vector3f e = lights[k].power;
                        if (lights[k].point) {
                            wi -= position;
                            const float r2 = wi.squaredNorm();
                            wi /= std::sqrt(r2);
                            e /= r2;
                        }
                        const float mu_i = n.dot(wi);
                        if (!(mu_i > 0.0F)) continue;
                        const Eigen::Vector3f wt = wi - mu_i * n;
                        const float wt_len = wt.norm();
                        const float cos_dphi = wt_len > 1e-6F ? wt.dot(t) / wt_len : 1.0F;
                        const Eigen::Vector3f f = lookupLight(light_table, ko, to, mu_i, cos_dphi);
                        l += (static_cast<float>(vis) * (1.0F / 255.0F) * mu_i) * f.cwiseProduct(e);
                    }
                    // Clear-coat mirror term.
                    const float* coat_o = coat + 3 * fineIndex(ko, to);
                    for (std::size_t c = 0; c < 3; ++c)
                        l[static_cast<Eigen::Index>(c)] +=
                            coat_o[c] * get<float>(rec + RecordLayout::kMirror + 4 * c);
                    float* px = image_base + 3 * static_cast<std::size_t>(pixel);
                    for (std::size_t c = 0; c < 3; ++c)
                        px[c] += halfToFloat(get<std::uint16_t>(rec + RecordLayout::kWeight + 2 * c)) *
                                 l[static_cast<Eigen::Index>(c)];
                }
            });
    });
    return image;
}

}  // namespace paintlab::raymaps
