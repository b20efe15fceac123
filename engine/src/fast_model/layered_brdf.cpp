#include "paintlab/engine/fast_model/layered_brdf.h"

#include "single_scattering.h"
#include "slab_operator.h"
#include "stack_assembly.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/fourier_series.h"
#include "paintlab/engine/optics/fresnel.h"

#include <tbb/parallel_for.h>

#include <optional>
#include <utility>
#include <variant>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>

namespace paintlab {

Preset presetFromName(std::string_view name) {
    if (name == "preview") return Preset::Preview;
    if (name == "standard") return Preset::Standard;
    if (name == "reference") return Preset::Reference;
    throw InputError("<argument>", "preset",
                     "unknown preset '" + std::string(name) + "' (expected preview, standard or reference)");
}

std::string_view presetName(Preset preset) {
    switch (preset) {
    case Preset::Preview:
        return "preview";
    case Preset::Standard:
        return "standard";
    case Preset::Reference:
        return "reference";
    }
    return "standard";
}

FastModelSettings presetSettings(Preset preset) {
    // Points on the measured accuracy-vs-time curves (tests/bench/bench_fast_model.cpp;
    // the figures: docs/PERFORMANCE.md, docs/CHANGELOG.md). The cheap presets'
    // colour error is mostly spectral (few bands), hence output_bands; the
    // angular grid converges fast. Preview spaces the flake kernel's azimuth
    // points one spread apart: a fifth less work.
    switch (preset) {
    case Preset::Preview:
        return {.nodes = 12,
                .orders = 8,
                .bands = 12,
                .max_start_tau = 1.0 / 32.0,
                .slices = 2,
                .flake_polar = 4,
                .flake_azimuth = 4,
                .flake_table = 17,
                .flake_kernel_points_per_spread = 1.0,
                .order_tolerance = 1e-3,
                .output_bands = 41,
                .flake_nodes_times_spread_deg = 80.0,
                .flake_orders_times_spread_deg = 56.0};
    case Preset::Standard:
        // Sharp lobes (g above ~0.65): within 2 % of the converged BRDF
        // wherever it is at least 1 % of its largest value at that incidence
        // (tests/engine/fast_model/test_sharp_phase.cpp).
        return {.nodes = 16,
                .orders = 8,
                .bands = 24,
                .max_start_tau = 1.0 / 64.0,
                .slices = 4,
                .flake_polar = 6,
                .flake_azimuth = 6,
                .flake_table = 33,
                .order_tolerance = 1e-4,
                .output_bands = 81,
                .sharp_nodes = 32,
                .sharp_orders = 24,
                .sharp_max_start_tau = 1.0 / 1024.0,
                // Narrow flakes: within ~0.1 ΔE00 of a 96-node, 64-order grid
                // down to a 2° spread (tests/engine/fast_model/test_narrow_flakes.cpp).
                .flake_nodes_times_spread_deg = 112.0,
                .flake_orders_times_spread_deg = 80.0};
    case Preset::Reference:
        // Converged: doubling nodes and orders (96, 64) changes the multi-angle
        // reflectance factors of the demo paints by < 3.2e-5, a 4x smaller start
        // by < 6e-7, a finer flake table and normal quadrature by < 2e-5.
        return {.nodes = 48,
                .orders = 32,
                .bands = 81,
                .max_start_tau = 1.0 / 4096.0,
                .slices = 8,
                .flake_polar = 16,
                .flake_azimuth = 16,
                .flake_table = 257,
                .order_tolerance = 1e-9,
                .output_bands = 0,
                // Sharp lobes (g above ~0.87): within 0.5 % everywhere.
                .sharp_nodes = 64,
                .sharp_orders = 48,
                .sharp_max_start_tau = 1.0 / 4096.0,
                .flake_nodes_times_spread_deg = 192.0,
                .flake_orders_times_spread_deg = 128.0};
    }
    return {};
}

namespace {

// The interpolation abscissae and pieces of the ambient's nodes (BandTable).
void setInterpolation(const fast::StackQuadrature& grid, const fast::MediumNodes& air,
                      LayeredBrdf::BandTable& table) {
    const double n_ref = grid.referenceIndex();
    table.reference_index = n_ref;
    const auto na = air.node.size();
    table.node_angle.resize(na);
    for (std::size_t k = 0; k < na; ++k) {
        const int node = air.node[k];
        table.node_angle[k] =
            std::atan2(grid.invariant(node) / n_ref, grid.muRef()[static_cast<std::size_t>(node)]);
    }
    table.piece_begin.clear();
    table.piece_mu_low.clear();
    for (std::size_t k = 0; k < na; ++k) {
        const int interval = grid.interval(air.node[k]);
        if (k == 0 || interval != grid.interval(air.node[k - 1])) {
            table.piece_begin.push_back(static_cast<int>(k));
            // The ambient's lowest node may sit in an interval that it only partly fills.
            table.piece_mu_low.push_back(k == 0 ? 0.0 : grid.intervalLow(interval));
        }
    }
    table.piece_begin.push_back(static_cast<int>(na));
    table.node_bary.assign(na, 1.0);
    table.mirror_bary.assign(na, 0.0);
    for (std::size_t p = 0; p + 1 < table.piece_begin.size(); ++p) {
        const auto b = static_cast<std::size_t>(table.piece_begin[p]);
        const auto e = static_cast<std::size_t>(table.piece_begin[p + 1]);
        // The piece holding the normal (angle 0) is mirrored: nodes +-theta.
        bool mirrored = false;
        for (std::size_t k = b; k < e; ++k) mirrored = mirrored || table.node_angle[k] == 0.0;
        std::vector<double> x(table.node_angle.begin() + static_cast<std::ptrdiff_t>(b),
                              table.node_angle.begin() + static_cast<std::ptrdiff_t>(e));
        if (mirrored)
            for (std::size_t k = b; k < e; ++k)
                if (table.node_angle[k] > 0.0) x.push_back(-table.node_angle[k]);
        // Each factor divided by the capacity (span / 4) of the abscissae: a
        // common scale, which the barycentric formula cancels, that keeps the
        // weights of a large piece (hundreds of nodes) from overflowing.
        const auto [lowest, highest] = std::minmax_element(x.begin(), x.end());
        const double capacity = std::max(*highest - *lowest, 1e-300) / 4.0;
        const auto weight = [&x, capacity](double xk) {
            double w = 1.0;
            for (double xl : x)
                if (xl != xk) w /= (xk - xl) / capacity;
            return w;
        };
        for (std::size_t k = b; k < e; ++k) {
            table.node_bary[k] = weight(table.node_angle[k]);
            if (mirrored && table.node_angle[k] > 0.0) table.mirror_bary[k] = weight(-table.node_angle[k]);
        }
    }
}

// One band's stack and the parts of its table that do not depend on the order.
struct BandWork {
    fast::BandStack stack;
    fast::MediumNodes air;
    double n_top = 1.0;
    int orders = 0;  // orders actually computed (the rest are negligible, see activeOrders)
};

// The number of leading Fourier orders worth computing: order m >= 1 is
// negligible when every slab's kernel is below tolerance x its order-0
// kernel and the substrate does not reflect in it; the kernels' Fourier
// coefficients fall monotonically with m (smooth lobes: HG's g^m, the
// flakes' Gaussian-like azimuthal lobes), so the first negligible order ends
// the series.
int activeOrders(const fast::BandStack& stack, const FastModelSettings& settings) {
    for (int m = 1; m < settings.orders; ++m) {
        if (stack.substrate[static_cast<std::size_t>(m)].cwiseAbs().maxCoeff() > 0.0) continue;
        bool negligible = true;
        for (const auto& element : stack.elements) {
            const auto* slab = std::get_if<fast::SlabElement>(&element);
            if (slab == nullptr) continue;
            const auto& k0 = slab->kernels.orders[0];
            const auto& km = slab->kernels.orders[static_cast<std::size_t>(m)];
            const double scale = std::max(k0.same.cwiseAbs().maxCoeff(), k0.opposite.cwiseAbs().maxCoeff());
            const double size = std::max(km.same.cwiseAbs().maxCoeff(), km.opposite.cwiseAbs().maxCoeff());
            if (size > settings.order_tolerance * scale) negligible = false;
        }
        if (negligible) return m;
    }
    return settings.orders;
}

BandWork prepareBand(const Recipe& recipe, double wavelength_nm, const FastModelSettings& settings,
                     LayeredBrdf::BandTable& table) {
    BandWork work{fast::buildBandStack(recipe, wavelength_nm, settings), {}, 0.0, 0};
    work.air = work.stack.grid.medium(work.stack.ambient_index);
    work.n_top = recipe.layers.front().binder.refractive_index(wavelength_nm);
    work.orders = activeOrders(work.stack, settings);
    const int na = static_cast<int>(work.air.node.size());
    table.mu = work.air.quadrature.mu;
    table.flux_weight.resize(na);
    for (int i = 0; i < na; ++i) table.flux_weight(i) = work.air.quadrature.fluxWeight(i);
    // The top interface's mirror term, reported apart from the BRDF.
    table.specular.resize(na);
    for (int i = 0; i < na; ++i)
        table.specular(i) =
            fresnelDielectric(table.mu[static_cast<std::size_t>(i)], work.n_top / work.stack.ambient_index);
    setInterpolation(work.stack.grid, work.air, table);
    // Orders not computed stay zero.
    table.f.assign(static_cast<std::size_t>(settings.orders), Eigen::MatrixXd::Zero(na, na));
    return work;
}

// f^m of one band (and its albedo for m = 0).
void tabulateOrder(const BandWork& work, int m, const FastModelSettings& settings,
                   LayeredBrdf::BandTable& table) {
    const Eigen::MatrixXd R = fast::stackReflection(work.stack, m, settings);
    const auto& air = work.air;
    const int na = static_cast<int>(air.node.size());
    Eigen::MatrixXd f(na, na);
    for (int i = 0; i < na; ++i)
        for (int j = 0; j < na; ++j)
            f(i, j) = R(air.node[static_cast<std::size_t>(i)], air.node[static_cast<std::size_t>(j)]);
    if (m == 0) table.albedo = f.colwise().sum().transpose();
    if (std::abs(work.n_top - work.stack.ambient_index) > 1e-9) f.diagonal() -= table.specular;
    // Flux-to-flux G to BRDF: f = G / (pi c_out) (a Lambertian G = rho c gives rho / pi).
    // Stored divided by the top interface's transmittance in and out: everything
    // below the coat leaves through it, and (1 - r(mu)) is what varies fast near
    // grazing, so the quotient is smooth and interpolates well.
    for (int i = 0; i < na; ++i) {
        f.row(i) /= std::numbers::pi * table.flux_weight(i) * (1.0 - table.specular(i));
        f.col(i) /= 1.0 - table.specular(i);
    }
    table.f[static_cast<std::size_t>(m)] = std::move(f);
}

// Interpolation basis of an ambient direction with cosine mu_ambient on the
// band's nodes: the barycentric Lagrange weights of its piece (BandTable),
// folded by parity for the mirrored piece: `even` for even Fourier orders,
// `odd` for odd ones. Both are resized to the node count; entries outside the
// piece are zero.
void interpolationBasis(const LayeredBrdf::BandTable& t, double ambient_index, double mu_ambient,
                        Eigen::VectorXd& even, Eigen::VectorXd& odd) {
    const auto na = static_cast<Eigen::Index>(t.mu.size());
    even.setZero(na);
    odd.setZero(na);
    if (na == 0) return;
    const double mu = std::clamp(mu_ambient, 0.0, 1.0);
    const double s = ambient_index * std::sqrt(std::max(0.0, 1.0 - mu * mu)) / t.reference_index;
    const double mu_ref = std::sqrt(std::max(0.0, 1.0 - s * s));
    const double x = std::atan2(s, mu_ref);
    std::size_t p = 0;
    while (p + 2 < t.piece_begin.size() && t.piece_mu_low[p + 1] <= mu_ref) ++p;
    const auto b = static_cast<Eigen::Index>(t.piece_begin[p]);
    const auto e = static_cast<Eigen::Index>(t.piece_begin[p + 1]);
    for (Eigen::Index k = b; k < e; ++k) {
        const double angle = t.node_angle[static_cast<std::size_t>(k)];
        if (x == angle) {  // on a node (also -angle: x >= 0 and angle 0 there)
            even.setZero();
            odd.setZero();
            even(k) = 1.0;
            odd(k) = angle == 0.0 ? 0.0 : 1.0;
            return;
        }
    }
    double sum = 0.0;
    for (Eigen::Index k = b; k < e; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const double plus = t.node_bary[kk] / (x - t.node_angle[kk]);
        const double minus = t.mirror_bary[kk] == 0.0 ? 0.0 : t.mirror_bary[kk] / (x + t.node_angle[kk]);
        even(k) = plus + minus;
        odd(k) = plus - minus;
        sum += plus + minus;
    }
    even /= sum;
    odd /= sum;
}

// The table at wavelength nm from the computed bands around it: 4-point
// Lagrange (cubic) weights in wavelength over the nearest computed bands, each
// band's f^m moved onto the grid of the nearest one by its own angular
// interpolation (the grids differ slightly with the binder's dispersion):
// f^m = sum_k c_k P_k f_k^m P_k^T, P_k the rows of interpolation bases of the
// target nodes in band k (even or odd by the order's parity). Tables are
// stored divided by the top interface's transmittance, so what is
// interpolated is the smooth part; the Fresnel terms are recomputed exactly.
LayeredBrdf::BandTable spectralInterpolation(const std::vector<double>& band_nm,
                                             const std::vector<LayeredBrdf::BandTable>& bands, double nm,
                                             double ambient_index, double n_top) {
    const int count = static_cast<int>(band_nm.size());
    int nearest = 0;
    for (int b = 1; b < count; ++b)
        if (std::abs(band_nm[static_cast<std::size_t>(b)] - nm) <
            std::abs(band_nm[static_cast<std::size_t>(nearest)] - nm))
            nearest = b;
    if (std::abs(band_nm[static_cast<std::size_t>(nearest)] - nm) < 1e-9)
        return bands[static_cast<std::size_t>(nearest)];
    // Four computed bands around nm (fewer if there are fewer).
    int width = std::min(4, count);
    int first = 0;
    while (first + 1 < count && band_nm[static_cast<std::size_t>(first) + 1] < nm) ++first;
    first = std::clamp(first - (width / 2 - 1), 0, count - width);
    if (nm < band_nm.front() || nm > band_nm.back()) {  // held constant beyond the computed range
        width = 1;
        first = nearest;
    }
    LayeredBrdf::BandTable t = bands[static_cast<std::size_t>(nearest)];  // grid and layout
    const auto na = static_cast<Eigen::Index>(t.mu.size());
    for (auto& f : t.f) f.setZero(na, na);
    t.albedo.setZero(na);
    Eigen::VectorXd even;
    Eigen::VectorXd odd;
    for (int k = first; k < first + width; ++k) {
        double c = 1.0;
        for (int l = first; l < first + width; ++l)
            if (l != k)
                c *= (nm - band_nm[static_cast<std::size_t>(l)]) /
                     (band_nm[static_cast<std::size_t>(k)] - band_nm[static_cast<std::size_t>(l)]);
        const auto& src = bands[static_cast<std::size_t>(k)];
        const auto ns = static_cast<Eigen::Index>(src.mu.size());
        Eigen::MatrixXd P_even(na, ns);
        Eigen::MatrixXd P_odd(na, ns);
        for (Eigen::Index i = 0; i < na; ++i) {
            interpolationBasis(src, ambient_index, t.mu[static_cast<std::size_t>(i)], even, odd);
            P_even.row(i) = even.transpose();
            P_odd.row(i) = odd.transpose();
        }
        for (std::size_t m = 0; m < t.f.size() && m < src.f.size(); ++m) {
            const Eigen::MatrixXd& P = m % 2 == 0 ? P_even : P_odd;
            t.f[m] += c * (P * src.f[m] * P.transpose());
        }
        t.albedo += c * (P_even * src.albedo);
    }
    for (Eigen::Index i = 0; i < na; ++i)
        t.specular(i) = fresnelDielectric(t.mu[static_cast<std::size_t>(i)], n_top / ambient_index);
    return t;
}

// The narrowest orientation spread of the recipe's flakes, degrees (0:
// aligned flakes, a mirror the grid need not resolve; infinity: no flakes).
double narrowestFlakeSpreadDeg(const Recipe& recipe) {
    double narrowest = std::numeric_limits<double>::infinity();
    for (const Layer& layer : recipe.layers)
        for (const Component& c : layer.components) {
            if (const auto* m = std::get_if<MirrorFlake>(&c))
                narrowest = std::min(narrowest, m->orientation_spread_deg);
            if (const auto* i = std::get_if<InterferenceFlake>(&c))
                narrowest = std::min(narrowest, i->orientation_spread_deg);
        }
    return narrowest;
}

// At least FastModelSettings::flake_*_times_spread_deg / spread nodes and
// orders for the narrowest flakes (nodes a multiple of 4, at most kMaxNodes).
FastModelSettings withNarrowFlakes(const Recipe& recipe, FastModelSettings settings) {
    const double spread = narrowestFlakeSpreadDeg(recipe);
    if (!(spread > 0.0) || !std::isfinite(spread)) return settings;
    if (settings.flake_nodes_times_spread_deg > 0.0) {
        const int nodes =
            4 * static_cast<int>(std::ceil(settings.flake_nodes_times_spread_deg / spread / 4.0));
        settings.nodes = std::max(settings.nodes, std::min({nodes, settings.flake_max_nodes, kMaxNodes}));
    }
    if (settings.flake_orders_times_spread_deg > 0.0) {
        const double orders = std::ceil(settings.flake_orders_times_spread_deg / spread);
        settings.orders =
            std::max(settings.orders,
                     static_cast<int>(std::min(orders, static_cast<double>(settings.flake_max_orders))));
    }
    return settings;
}

}  // namespace

double narrowestResolvedFlakeSpreadDeg(const FastModelSettings& settings) {
    return std::max(settings.flake_nodes_times_spread_deg / kMaxNodes,
                    settings.flake_orders_times_spread_deg / (2.0 * kMaxNodes));
}

namespace {

// The settings a recipe runs with: the preset's, with the finer grid of
// FastModelSettings::sharp_* if a pigment's phase function is sharp there
// (its delta-M truncation, checked at five wavelengths across the range),
// and of flake_*_times_spread_deg for narrow flakes.
FastModelSettings settingsFor(const Recipe& recipe, const FastModelSettings& requested) {
    const FastModelSettings settings = withNarrowFlakes(recipe, requested);
    if (settings.sharp_nodes <= settings.nodes && settings.sharp_orders <= settings.orders &&
        settings.sharp_max_start_tau >= settings.max_start_tau)
        return settings;
    double truncated = 0.0;
    for (const Layer& layer : recipe.layers)
        for (double nm : visibleBands(5)) {
            const SlabOptics optics = slabOptics(layer, nm);
            if (optics.sigma_s_per_um > 0.0)
                truncated = std::max(truncated, fast::scaledMedium(optics, settings.nodes).f);
        }
    if (truncated <= settings.sharp_truncation) return settings;
    FastModelSettings sharp = settings;
    sharp.nodes = std::max(settings.nodes, std::min(settings.sharp_nodes, kMaxNodes));
    sharp.orders = std::max(settings.orders, settings.sharp_orders);
    sharp.max_start_tau = std::min(settings.max_start_tau, settings.sharp_max_start_tau);
    return sharp;
}

// The wavelengths the model runs at: spread evenly over the whole visible
// range 380-780 nm (spectrum.h), with or without spectral refinement, so the
// refined tables interpolate between computed bands everywhere and never hold
// an end value (measured cost and colour error: docs/PERFORMANCE.md).
std::vector<double> computedBands(const FastModelSettings& settings) {
    return visibleBands(static_cast<std::size_t>(std::max(2, settings.bands)));
}

}  // namespace

LayeredBrdf computeLayeredBrdf(const Recipe& recipe, const FastModelSettings& requested,
                               const ProgressCallback& progress) {
    // The tables are interpolated by one polynomial per quadrature interval
    // (setInterpolation); through more than ~100 of these nodes it is
    // ill-conditioned (from 100 nodes on, values at grazing angles go wrong).
    if (requested.nodes > kMaxNodes)
        throw InputError("<settings>", "nodes",
                         std::to_string(requested.nodes) + " is more than the " + std::to_string(kMaxNodes) +
                             " the tables' interpolation takes");
    const FastModelSettings settings = settingsFor(recipe, requested);
    const auto start = std::chrono::steady_clock::now();
    LayeredBrdf brdf;
    brdf.m_settings = settings;
    brdf.m_wavelengths_nm = computedBands(settings);
    brdf.m_ambient_index = recipe.ambient_refractive_index;
    brdf.m_bands.resize(brdf.m_wavelengths_nm.size());
    std::atomic<bool> cancelled{false};
    std::atomic<int> done{0};
    std::mutex progress_mutex;
    const auto count = static_cast<int>(brdf.m_wavelengths_nm.size());
    // Stage 1, per band: the stack (slab kernels) and the order-free table parts.
    std::vector<std::optional<BandWork>> work(static_cast<std::size_t>(count));
    tbb::parallel_for(0, count, [&](int b) {
        const auto k = static_cast<std::size_t>(b);
        work[k].emplace(prepareBand(recipe, brdf.m_wavelengths_nm[k], settings, brdf.m_bands[k]));
    });
    // Stage 2: the (band, order) pairs are independent; one task each, so
    // both cores stay busy however bands and orders are balanced (Eigen runs
    // single-threaded inside).
    std::vector<std::pair<int, int>> pairs;
    for (int b = 0; b < count; ++b)
        for (int m = 0; m < work[static_cast<std::size_t>(b)]->orders; ++m) pairs.emplace_back(b, m);
    const auto total = static_cast<int>(pairs.size());
    tbb::parallel_for(0, total, [&](int p) {
        if (cancelled.load()) return;
        const auto [b, m] = pairs[static_cast<std::size_t>(p)];
        tabulateOrder(*work[static_cast<std::size_t>(b)], m, settings,
                      brdf.m_bands[static_cast<std::size_t>(b)]);
        const int finished = ++done;
        if (progress) {
            const std::lock_guard lock(progress_mutex);
            if (!progress(double(finished) / total)) cancelled = true;
        }
    });
    if (cancelled) throw Error("fast model: cancelled");
    if (settings.output_bands > count) {
        // Spectral refinement of the tables (FastModelSettings::output_bands).
        const std::vector<double> out_nm = visibleBands(static_cast<std::size_t>(settings.output_bands));
        std::vector<LayeredBrdf::BandTable> out(out_nm.size());
        tbb::parallel_for(0, static_cast<int>(out_nm.size()), [&](int o) {
            const auto k = static_cast<std::size_t>(o);
            out[k] =
                spectralInterpolation(brdf.m_wavelengths_nm, brdf.m_bands, out_nm[k], brdf.m_ambient_index,
                                      recipe.layers.front().binder.refractive_index(out_nm[k]));
        });
        brdf.m_wavelengths_nm = out_nm;
        brdf.m_bands = std::move(out);
    }
    for (double nm : brdf.m_wavelengths_nm)
        brdf.m_top_index_per_band.push_back(recipe.layers.front().binder.refractive_index(nm));
    if (settings.exact_single_scattering) {
        // Per output band, with the orders its nearest computed band's table holds.
        std::vector<double> computed_nm = computedBands(settings);
        std::vector<std::optional<fast::SingleScatteringCorrection>> corrections(
            brdf.m_wavelengths_nm.size());
        tbb::parallel_for(0, static_cast<int>(corrections.size()), [&](int o) {
            const auto k = static_cast<std::size_t>(o);
            const double nm = brdf.m_wavelengths_nm[k];
            std::size_t nearest = 0;
            for (std::size_t b = 1; b < computed_nm.size(); ++b)
                if (std::abs(computed_nm[b] - nm) < std::abs(computed_nm[nearest] - nm)) nearest = b;
            corrections[k].emplace(recipe, nm, settings, work[nearest]->orders);
        });
        if (std::any_of(corrections.begin(), corrections.end(), [](const auto& c) { return !c->empty(); })) {
            auto all = std::make_shared<std::vector<fast::SingleScatteringCorrection>>();
            for (auto& c : corrections) all->push_back(std::move(*c));
            brdf.m_single_scattering = std::move(all);
        }
    }
    brdf.m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return brdf;
}

LayeredBrdf LayeredBrdf::withTables(const LayeredBrdf& grid, std::vector<BandTable> tables, double seconds) {
    if (tables.size() != grid.m_bands.size())
        throw InputError("tables", "bands", "expected " + std::to_string(grid.m_bands.size()) + " bands");
    for (std::size_t b = 0; b < tables.size(); ++b) {
        const BandTable& g = grid.m_bands[b];
        BandTable& t = tables[b];
        const auto n = static_cast<Eigen::Index>(g.mu.size());
        if (t.f.size() != g.f.size() || t.albedo.size() != n)
            throw InputError("tables", "f",
                             "band " + std::to_string(b) + " does not match the grid's orders or nodes");
        for (const Eigen::MatrixXd& fm : t.f)
            if (fm.rows() != n || fm.cols() != n)
                throw InputError("tables", "f",
                                 "band " + std::to_string(b) + " does not match the grid's nodes");
        // Everything but the estimates comes from the grid.
        t.mu = g.mu;
        t.specular = g.specular;
        t.flux_weight = g.flux_weight;
        t.reference_index = g.reference_index;
        t.node_angle = g.node_angle;
        t.node_bary = g.node_bary;
        t.mirror_bary = g.mirror_bary;
        t.piece_begin = g.piece_begin;
        t.piece_mu_low = g.piece_mu_low;
    }
    LayeredBrdf brdf = grid;
    brdf.m_bands = std::move(tables);
    brdf.m_single_scattering.reset();
    brdf.m_seconds = seconds;
    return brdf;
}

void LayeredBrdf::eval(const Direction& wi, const Direction& wo, std::span<double> out) const {
    std::fill(out.begin(), out.end(), 0.0);
    if (!(wi.z > 0.0) || !(wo.z > 0.0)) return;
    // Azimuth difference of the propagation directions: the light travels along
    // -wi (azimuth phi_i + pi), so delta = phi_o - phi_i - pi and cos(m delta) = (-1)^m cos(m (phi_o -
    // phi_i)).
    const double phi_i = std::atan2(wi.y, wi.x);
    const double phi_o = std::atan2(wo.y, wo.x);
    const double dphi = phi_o - phi_i;
    Eigen::VectorXd out_even;
    Eigen::VectorXd out_odd;
    Eigen::VectorXd in_even;
    Eigen::VectorXd in_odd;
    std::vector<double> terms;  // per order: 1 for m = 0, 2 (-1)^m cos(m dphi) for m > 0
    std::vector<double> coefficients;
    for (std::size_t b = 0; b < m_bands.size() && b < out.size(); ++b) {
        const BandTable& t = m_bands[b];
        interpolationBasis(t, m_ambient_index, wo.z, out_even, out_odd);
        interpolationBasis(t, m_ambient_index, wi.z, in_even, in_odd);
        const double eta = m_top_index_per_band[b] / m_ambient_index;
        const double transmit = (1.0 - fresnelDielectric(wi.z, eta)) * (1.0 - fresnelDielectric(wo.z, eta));
        for (std::size_t m = terms.size(); m < t.f.size(); ++m) {
            const double sign = (m % 2 == 0) ? 1.0 : -1.0;
            terms.push_back(m == 0 ? 1.0 : 2.0 * sign * std::cos(double(m) * dphi));
        }
        coefficients.resize(t.f.size());
        for (std::size_t m = 0; m < t.f.size(); ++m)
            coefficients[m] = m % 2 == 0 ? out_even.dot(t.f[m] * in_even) : out_odd.dot(t.f[m] * in_odd);
        const double correction = m_single_scattering ? (*m_single_scattering)[b](wi.z, wo.z, dphi) : 0.0;
        out[b] = std::max(
            0.0, fourierSum(std::span<const double>(terms).first(t.f.size()), coefficients, 1, transmit) +
                     correction);
    }
}

std::vector<double> LayeredBrdf::specularReflectance(double cos_theta) const {
    std::vector<double> r;
    for (double n_top : m_top_index_per_band)
        r.push_back(fresnelDielectric(cos_theta, n_top / m_ambient_index));
    return r;
}

int LayeredBrdf::orders() const {
    std::size_t orders = 0;
    for (const BandTable& t : m_bands) orders = std::max(orders, t.f.size());
    return static_cast<int>(orders);
}

void LayeredBrdf::fourierCoefficients(double cos_o, double cos_i, std::span<double> out) const {
    const std::size_t bands = m_bands.size();
    const auto orders = static_cast<std::size_t>(this->orders());
    if (out.size() < orders * bands)
        throw InputError("<argument>", "out",
                         "needs orders x bands = " + std::to_string(orders * bands) + " values");
    std::fill(out.begin(), out.end(), 0.0);
    if (!(cos_o > 0.0) || !(cos_i > 0.0)) return;
    Eigen::VectorXd out_even;
    Eigen::VectorXd out_odd;
    Eigen::VectorXd in_even;
    Eigen::VectorXd in_odd;
    std::vector<double> correction(m_single_scattering ? orders : 0);
    for (std::size_t b = 0; b < bands; ++b) {
        const BandTable& t = m_bands[b];
        interpolationBasis(t, m_ambient_index, std::min(cos_o, 1.0), out_even, out_odd);
        interpolationBasis(t, m_ambient_index, std::min(cos_i, 1.0), in_even, in_odd);
        const double eta = m_top_index_per_band[b] / m_ambient_index;
        const double transmit = (1.0 - fresnelDielectric(cos_i, eta)) * (1.0 - fresnelDielectric(cos_o, eta));
        // As in eval(): weight 1 for m = 0 and 2 (-1)^m for m > 0 (the sign
        // turns the propagation azimuth of the incident light into that of wi).
        for (std::size_t m = 0; m < t.f.size(); ++m) {
            const double weight = m == 0 ? 1.0 : (m % 2 == 0 ? 2.0 : -2.0);
            const double value = m % 2 == 0 ? out_even.dot(t.f[m] * in_even) : out_odd.dot(t.f[m] * in_odd);
            out[m * bands + b] = transmit * weight * value;
        }
        if (m_single_scattering) {
            (*m_single_scattering)[b].fourierCoefficients(cos_i, std::min(cos_o, 1.0), correction);
            for (std::size_t m = 0; m < orders; ++m) out[m * bands + b] += correction[m];
        }
    }
}

void LayeredBrdf::fourierCoefficientsGrid(std::span<const double> cos_o, std::span<const double> cos_i,
                                          const Eigen::MatrixXd& weights, std::span<double> out) const {
    const std::size_t bands = m_bands.size();
    const auto orders = static_cast<std::size_t>(this->orders());
    const std::size_t n_o = cos_o.size();
    const std::size_t n_i = cos_i.size();
    const auto channels = static_cast<std::size_t>(weights.cols());
    if (static_cast<std::size_t>(weights.rows()) != bands)
        throw InputError("<argument>", "weights", "needs one row per band (" + std::to_string(bands) + ")");
    if (out.size() < n_o * n_i * orders * channels)
        throw InputError("<argument>", "out",
                         "needs cos_o x cos_i x orders x channels = " +
                             std::to_string(n_o * n_i * orders * channels) + " values");
    std::fill(out.begin(), out.end(), 0.0);
    // Per band: the bases of the incident cosines as the columns of one
    // matrix per parity, and their Fresnel transmittances.
    struct Incident {
        Eigen::MatrixXd even, odd;
        std::vector<double> transmit;
    };
    std::vector<Incident> incident(bands);
    for (std::size_t b = 0; b < bands; ++b) {
        const BandTable& t = m_bands[b];
        const auto n = static_cast<Eigen::Index>(t.mu.size());
        const double eta = m_top_index_per_band[b] / m_ambient_index;
        Incident& in = incident[b];
        in.even.resize(n, static_cast<Eigen::Index>(n_i));
        in.odd.resize(n, static_cast<Eigen::Index>(n_i));
        in.transmit.assign(n_i, 0.0);
        Eigen::VectorXd even;
        Eigen::VectorXd odd;
        for (std::size_t i = 0; i < n_i; ++i) {
            interpolationBasis(t, m_ambient_index, std::min(cos_i[i], 1.0), even, odd);
            in.even.col(static_cast<Eigen::Index>(i)) = even;
            in.odd.col(static_cast<Eigen::Index>(i)) = odd;
            in.transmit[i] = cos_i[i] > 0.0 ? 1.0 - fresnelDielectric(cos_i[i], eta) : 0.0;
        }
    }
    // Each outgoing cosine writes its own slice of `out`. As in
    // fourierCoefficients(): weight 1 for m = 0 and 2 (-1)^m for m > 0.
    tbb::parallel_for(std::size_t{0}, n_o, [&](std::size_t o) {
        if (!(cos_o[o] > 0.0)) return;
        Eigen::VectorXd even;
        Eigen::VectorXd odd;
        Eigen::RowVectorXd row;
        Eigen::RowVectorXd values(static_cast<Eigen::Index>(n_i));
        std::vector<double> correction(orders);
        for (std::size_t b = 0; b < bands; ++b) {
            const BandTable& t = m_bands[b];
            const Incident& in = incident[b];
            interpolationBasis(t, m_ambient_index, std::min(cos_o[o], 1.0), even, odd);
            const double transmit_o =
                1.0 - fresnelDielectric(cos_o[o], m_top_index_per_band[b] / m_ambient_index);
            for (std::size_t m = 0; m < t.f.size(); ++m) {
                const double weight = m == 0 ? 1.0 : (m % 2 == 0 ? 2.0 : -2.0);
                if (m % 2 == 0) {
                    row.noalias() = even.transpose() * t.f[m];
                    values.noalias() = row * in.even;
                } else {
                    row.noalias() = odd.transpose() * t.f[m];
                    values.noalias() = row * in.odd;
                }
                for (std::size_t i = 0; i < n_i; ++i) {
                    const double v =
                        transmit_o * in.transmit[i] * weight * values(static_cast<Eigen::Index>(i));
                    double* at = out.data() + ((o * n_i + i) * orders + m) * channels;
                    for (std::size_t c = 0; c < channels; ++c)
                        at[c] += weights(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(c)) * v;
                }
            }
            if (!m_single_scattering) continue;
            for (std::size_t i = 0; i < n_i; ++i) {
                (*m_single_scattering)[b].fourierCoefficients(std::min(cos_i[i], 1.0),
                                                              std::min(cos_o[o], 1.0), correction);
                for (std::size_t m = 0; m < orders; ++m) {
                    double* at = out.data() + ((o * n_i + i) * orders + m) * channels;
                    for (std::size_t c = 0; c < channels; ++c)
                        at[c] += weights(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(c)) *
                                 correction[m];
                }
            }
        }
    });
}

std::vector<double> LayeredBrdf::albedo(const Direction& wi) const {
    std::vector<double> a;
    Eigen::VectorXd even;
    Eigen::VectorXd odd;
    for (const auto& t : m_bands) {
        interpolationBasis(t, m_ambient_index, wi.z, even, odd);  // the albedo is even in theta
        a.push_back(even.dot(t.albedo));
    }
    return a;
}

std::vector<double> LayeredBrdf::diffuseAlbedo() const {
    std::vector<double> a;
    for (const auto& t : m_bands) a.push_back(t.albedo.dot(t.flux_weight));
    return a;
}

}  // namespace paintlab
