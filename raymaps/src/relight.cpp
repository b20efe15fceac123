// Relight: the recipe's tables (cost independent of the image) and the pass
// over the paint records (docs/RAYMAPS.md, "Relight").

#include "relight_grid.h"
#include "sampling.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

namespace paintlab::raymaps {

namespace {

using grid::kC;
using grid::kF;
using grid::kN;

// 8-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 8> kGaussX{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                        -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                        0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGaussW{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                        0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                        0.2223810344533745, 0.1012285362903763};

// i * n + m in size_t.
std::size_t index2(int i, int n, int m) {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(m);
}

}  // namespace

RelightTables::RelightTables(const LayeredBrdf& brdf, int cells, int orders)
    : m_cells(cells), m_orders(orders) {
    if (cells < 1 || cells > 16 || orders < 1 || orders > 16)
        throw InputError("<argument>", "cells/orders", "J must be in [1, 16] and M_L in [1, 16]");
    const auto start = std::chrono::steady_clock::now();
    const auto wavelengths = brdf.wavelengthsNm();
    const std::size_t bands = wavelengths.size();
    // Linear sRGB of each band (D65 / 2 degrees, white -> (1, 1, 1)).
    m_weights = bandColourWeights(wavelengths);
    // Orders kept: at least 8 (the light table sums them at kC azimuths).
    const int n_phi = std::max(8, brdf.settings().orders);
    const auto nu = static_cast<std::size_t>(kN);
    m_light.assign(nu * nu * static_cast<std::size_t>(kC) * 4, 0.0F);
    // cos(m dphi) at the azimuth nodes, once (not kN^2 times).
    std::vector<double> cosines(static_cast<std::size_t>(kC) * static_cast<std::size_t>(n_phi));
    for (int c = 0; c < kC; ++c)
        for (int m = 0; m < n_phi; ++m) cosines[index2(c, n_phi, m)] = std::cos(m * kPi * c / (kC - 1));
    const std::size_t per_node = static_cast<std::size_t>(cells) * static_cast<std::size_t>(orders) * 3;
    std::vector<float> moments(nu * per_node, 0.0F);
    std::vector<float> coats(nu * 3, 0.0F);

    // Fourier cosine coefficients of f_rgb(mu_o, mu_i, phi) = sum_m a_m
    // cos(m phi) at every node pair, straight from the fast model's tables
    // and reduced to linear sRGB there (one basis per cosine, one product per
    // order, band and mu_o; pair by pair it cost 20x more).
    const auto series_orders = static_cast<std::size_t>(brdf.orders());
    std::vector<double> mu_nodes(nu);
    for (int k = 0; k < kN; ++k) mu_nodes[static_cast<std::size_t>(k)] = grid::muNode(k);
    Eigen::MatrixXd weights(static_cast<Eigen::Index>(bands), 3);
    for (std::size_t b = 0; b < bands; ++b) {
        const Rgb& c = m_weights.linear_srgb[b];
        weights.row(static_cast<Eigen::Index>(b)) << c.r, c.g, c.b;
    }
    std::vector<double> series(nu * nu * series_orders * 3);
    brdf.fourierCoefficientsGrid(mu_nodes, mu_nodes, weights, series);

    tbb::parallel_for(0, kN, [&](int o) {
        std::vector<Rgb3> a(static_cast<std::size_t>(n_phi));
        std::vector<Rgb3> node_a(static_cast<std::size_t>(kN * orders),
                                 Rgb3::Zero());  // a_m at the theta_i nodes
        const auto coefficients = [&](int i) {
            for (int m = 0; m < n_phi; ++m) {
                const auto mm = static_cast<std::size_t>(m);
                if (mm >= series_orders) {
                    a[mm] = Rgb3::Zero();
                    continue;
                }
                const double* at =
                    series.data() +
                    ((static_cast<std::size_t>(o) * nu + static_cast<std::size_t>(i)) * series_orders + mm) *
                        3;
                a[mm] = Rgb3(at[0], at[1], at[2]);
            }
        };
        for (int i = 0; i < kN; ++i) {
            coefficients(i);
            for (int m = 0; m < orders && m < n_phi; ++m)
                node_a[index2(i, orders, m)] = a[static_cast<std::size_t>(m)];
            for (int c = 0; c < kC; ++c) {
                Rgb3 value = Rgb3::Zero();
                for (int m = 0; m < n_phi; ++m)
                    value += a[static_cast<std::size_t>(m)] * cosines[index2(c, n_phi, m)];
                float* node = m_light.data() + grid::lightNode(o, i, c);
                for (int ch = 0; ch < 3; ++ch) node[ch] = static_cast<float>(std::max(0.0, value[ch]));
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
        const Rgb3 coat = toRgb(brdf.specularReflectance(grid::muNode(o)));
        for (int ch = 0; ch < 3; ++ch)
            coats[3 * static_cast<std::size_t>(o) + static_cast<std::size_t>(ch)] =
                static_cast<float>(coat[ch]);
    });
    // Resampled on the fine grid (see kFineNodes), m >= 1 scaled by 1/127,
    // in the kernel's order [o][channel][m][j].
    m_moments.assign(static_cast<std::size_t>(kF) * per_node, 0.0F);
    m_coat.assign(static_cast<std::size_t>(kF) * 3, 0.0F);
    for (int f = 0; f < kF; ++f) {
        const double x = std::min(static_cast<double>(f) * (kN - 1) / (kF - 1), kN - 1 - 1e-9);
        const auto k = static_cast<std::size_t>(x);
        const auto t = static_cast<float>(x - static_cast<double>(k));
        const auto uf = static_cast<std::size_t>(f);
        const auto uj = static_cast<std::size_t>(cells);
        const auto um = static_cast<std::size_t>(orders);
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t m = 0; m < um; ++m)
                for (std::size_t j = 0; j < uj; ++j) {
                    const std::size_t from = (j * um + m) * 3 + c;  // coarse: [o][j][m][channel]
                    m_moments[((uf * 3 + c) * um + m) * uj + j] =
                        ((1.0F - t) * moments[k * per_node + from] + t * moments[(k + 1) * per_node + from]) *
                        (m == 0 ? 1.0F : 1.0F / 127.0F);
                }
        for (std::size_t c = 0; c < 3; ++c)
            m_coat[uf * 3 + c] = (1.0F - t) * coats[k * 3 + c] + t * coats[(k + 1) * 3 + c];
    }
    m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Rgb3 RelightTables::toRgb(const std::vector<double>& spectrum) const {
    const Rgb c = weightedLinearSrgb(m_weights, spectrum);
    return {c.r, c.g, c.b};
}

Rgb3 RelightTables::lightTable(double mu_o, double mu_i, double cos_dphi) const {
    int ko = 0;
    int ki = 0;
    int kc = 0;
    float to = 0.0F;
    float ti = 0.0F;
    float tc = 0.0F;
    grid::muIndex(mu_o, ko, to);
    grid::muIndex(mu_i, ki, ti);
    grid::phiIndex(cos_dphi, kc, tc);
    std::array<float, 4> f{};
    grid::trilinear(m_light.data() + grid::lightNode(ko, ki, kc), to, ti, tc, f.data());
    return Eigen::Vector3f(f[0], f[1], f[2]).cast<double>();
}

Rgb3 RelightTables::coat(double mu_o) const {
    int k = 0;
    float t = 0.0F;
    grid::muIndex(std::clamp(mu_o, 0.0, 1.0), k, t);
    const std::size_t f = 3 * grid::fineIndex(k, t);
    return Eigen::Vector3f(m_coat[f], m_coat[f + 1], m_coat[f + 2]).cast<double>();
}

namespace {

// The decoded paint pixels (RelightInput's arrays, relight_input.h).
struct RelightArrays {
    const std::uint32_t* pixel;
    const std::uint32_t* fine;
    const float* to;
    const float* l0;
    const std::int8_t* q;
    const float* mirror;
    const std::uint32_t* light_at;
    const float* light_t;
    const float* light_s;
};

// The kernel over the paint pixels of rows [y0, y1), added to the baked
// radiance already in `image`: per paint pixel
//   L_c = sum_j l0_cj (fbar^0_cj + sum_{m>=1} fbar^m_cj q_cmj)       (moments)
//       + sum_k s_kc f_c(trilinear at the light's corner)           (explicit lights)
//       + R_coat,c mirror_c                                          (clear coat)
// with the pixel's weight already in l0, s and mirror. No branch depends on
// the data; kJ, kM > 0 fix J and M_L at compile time (the default 4 x 4 is
// unrolled and vectorised by the compiler: SSE over j and over the light
// table's 4 lanes), 0 takes them from the input.
template <int kJ, int kM> void shadeRows(const RelightInput& in, const std::vector<std::size_t>& row_start,
                                         const RelightArrays& a, const RelightTables& tables, int y0, int y1,
                                         float* image) {
    const std::size_t cells = kJ > 0 ? static_cast<std::size_t>(kJ) : static_cast<std::size_t>(in.cells());
    const std::size_t orders = kM > 0 ? static_cast<std::size_t>(kM) : static_cast<std::size_t>(in.orders());
    const auto lights = static_cast<std::size_t>(in.lights());
    const float* moments = tables.moments().data();
    const float* coat = tables.coat().data();
    const float* light = tables.light().data();
    const std::size_t moment_stride = 3 * orders * cells;
    constexpr std::size_t kMaxCells = 16;
    for (std::size_t i = row_start[static_cast<std::size_t>(y0)]; i < row_start[static_cast<std::size_t>(y1)];
         ++i) {
        const std::size_t fine = a.fine[i];
        const float* mt = moments + fine * moment_stride;
        const float* l0 = a.l0 + i * 3 * cells;
        const std::int8_t* q = a.q + i * 3 * (orders - 1) * cells;
        std::array<float, 4> l{};
        for (std::size_t c = 0; c < 3; ++c) {
            const float* tc = mt + c * orders * cells;
            const std::int8_t* qc = q + c * (orders - 1) * cells;
            std::array<float, kMaxCells> acc{};
            for (std::size_t j = 0; j < cells; ++j) acc[j] = tc[j];
            for (std::size_t m = 1; m < orders; ++m)
                for (std::size_t j = 0; j < cells; ++j)
                    acc[j] += tc[m * cells + j] * static_cast<float>(qc[(m - 1) * cells + j]);
            float sum = 0.0F;
            for (std::size_t j = 0; j < cells; ++j) sum += l0[c * cells + j] * acc[j];
            l[c] = sum + coat[3 * fine + c] * a.mirror[3 * i + c];
        }
        const float to = a.to[i];
        for (std::size_t k = 0; k < lights; ++k) {
            const std::size_t ik = i * lights + k;
            std::array<float, 4> f{};
            grid::trilinear(light + a.light_at[ik], to, a.light_t[2 * ik], a.light_t[2 * ik + 1], f.data());
            for (std::size_t c = 0; c < 3; ++c) l[c] += a.light_s[3 * ik + c] * f[c];
        }
        float* px = image + 3 * static_cast<std::size_t>(a.pixel[i]);
        for (std::size_t c = 0; c < 3; ++c) px[c] += l[c];
    }
}

}  // namespace

RgbImage relight(const RelightInput& in, const RelightTables& tables) {
    if (in.cells() != tables.cells() || in.orders() != tables.orders())
        throw InputError("<ray map>", "header",
                         "the map has J = " + std::to_string(in.cells()) +
                             ", M_L = " + std::to_string(in.orders()) +
                             "; the relight tables were built for J = " + std::to_string(tables.cells()) +
                             ", M_L = " + std::to_string(tables.orders()));
    RgbImage image;
    image.width = in.width();
    image.height = in.height();
    image.rgb.assign(in.m_baked.begin(), in.m_baked.end());  // the paint is added below
    const RelightArrays arrays{in.m_pixel.data(),    in.m_fine.data(),    in.m_to.data(),
                               in.m_l0.data(),       in.m_q.data(),       in.m_mirror.data(),
                               in.m_light_at.data(), in.m_light_t.data(), in.m_light_s.data()};
    const bool fixed = in.cells() == 4 && in.orders() == 4;
    tbb::parallel_for(tbb::blocked_range<int>(0, in.height(), 8), [&](const tbb::blocked_range<int>& rows) {
        if (fixed)
            shadeRows<4, 4>(in, in.m_row_start, arrays, tables, rows.begin(), rows.end(), image.rgb.data());
        else
            shadeRows<0, 0>(in, in.m_row_start, arrays, tables, rows.begin(), rows.end(), image.rgb.data());
    });
    return image;
}

RgbImage relight(const RayMap& map, const RelightTables& tables) {
    const RayMapHeader& h = map.header();
    if (h.cells != tables.cells() || h.orders != tables.orders())
        throw InputError(map.path().string(), "header",
                         "the map has J = " + std::to_string(h.cells) +
                             ", M_L = " + std::to_string(h.orders) +
                             "; the relight tables were built for J = " + std::to_string(tables.cells()) +
                             ", M_L = " + std::to_string(tables.orders()));
    return relight(RelightInput(map), tables);
}

}  // namespace paintlab::raymaps
