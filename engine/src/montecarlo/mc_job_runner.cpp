#include "mc_job_runner.h"

#include "paintlab/engine/optics/fresnel.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

// First-flake walks: the weight, in draws, of the mean over all keys in a key's learned weight.
constexpr double kFirstFlakePrior = 64.0;

// Whether a delta chain can begin other than at an explicit flake: an index
// step inside the paint (an internal reflection of the beam) or a mirror-like
// substrate. Otherwise the first-flake walks hold every delta chain and the
// uniform delta-chain walks are not run.
bool otherDeltaStarts(const PaintStack& stack) {
    for (std::size_t j = 0; j + 1 < stack.slices.size(); ++j)
        if (std::abs(stack.slices[j].n - stack.slices[j + 1].n) >= 1e-12) return true;
    return stack.substrate == SubstrateKind::Metal || stack.substrate == SubstrateKind::Transparent;
}

}  // namespace

JobRunner::JobRunner(const McEngine::Band& band, const JobSpec& job, const McSettings& settings,
                     double tile_side_um, std::uint64_t band_key, std::uint64_t incidence_key)
    : m_band(band), m_settings(settings), m_tile_side_um(tile_side_um), m_band_key(band_key),
      m_incidence_key(incidence_key) {
    const PaintStack& stack = band.stack;
    if (settings.histogram_cone_deg > 0.0) {
        const double alpha = settings.histogram_cone_deg * std::numbers::pi / 180.0;
        for (const auto& wo : job.wo)
            m_bins.push_back({{wo.x, wo.y, wo.z},
                              std::cos(alpha),
                              std::numbers::pi * std::sin(alpha) * std::sin(alpha) * std::max(wo.z, 1e-9),
                              2.0 * std::numbers::pi * (1.0 - std::cos(alpha))});
    } else {
        for (const auto& wo : job.wo) m_chains.push_back(exitChain(stack, wo));
    }
    m_exits = job.wo.size();
    const Direction& wi = job.wi;
    const double n1 = stack.slices.front().n;
    const double mu_i = std::clamp(wi.z, 0.0, 1.0);
    m_specular = std::abs(n1 - stack.ambient_n) < 1e-12 ? 0.0 : fresnelDielectric(mu_i, n1 / stack.ambient_n);
    m_entry_weight = mu_i > 0.0 ? 1.0 - m_specular : 0.0;
    // The beam travels along -wi; refracted into the top binder.
    const double ratio = stack.ambient_n / n1;
    m_v_in = {-wi.x * ratio, -wi.y * ratio, 0.0};
    m_v_in.z = -std::sqrt(std::max(0.0, 1.0 - m_v_in.x * m_v_in.x - m_v_in.y * m_v_in.y));
    if (!job.cell_upper_mu.empty() && job.orders > 0 && m_entry_weight > 0.0) {
        m_cells.upper_mu = job.cell_upper_mu;
        m_cells.orders = job.orders;
        m_cells.top_eta = n1 / stack.ambient_n;
        const double s = std::hypot(wi.x, wi.y);
        m_cells.cos_in = s > 0.0 ? -wi.x / s : 1.0;
        m_cells.sin_in = s > 0.0 ? -wi.y / s : 0.0;
        m_cells.offset = m_exits;  // in f_out, which starts at kFirstExit
        for (std::size_t c = 0; c < job.cell_upper_mu.size(); ++c) {
            const double lo = job.cell_lower_mu[c];
            const double hi = job.cell_upper_mu[c];
            m_cells.scale.push_back(1.0 / (std::numbers::pi * (hi * hi - lo * lo) * m_entry_weight));
        }
        m_projected = m_cells.scale.size() * static_cast<std::size_t>(job.orders);
    }
    m_connections = settings.connections && settings.explicit_flakes && !m_bins.empty() &&
                    !band.explicit_flakes.empty() && m_entry_weight > 0.0;
    m_connection_fraction = std::clamp(settings.connection_fraction, 1e-3, 1.0);
    const double nee_rate = std::clamp(settings.connection_fraction, 1e-3, kMaxNeeRate);
    m_azimuths = m_connections && settings.glint_azimuths;
    m_move_glint_flakes = m_azimuths && settings.move_glint_flakes && !settings.reject_overlaps;
    m_adaptive = m_azimuths && settings.adaptive_fractions;
    m_rates.nee_fraction.assign(m_exits, nee_rate);
    m_rates.glint_rate.assign(m_exits, m_connection_fraction);
    m_reverse = m_azimuths && settings.reverse_walks && settings.connection_parts.reverse_walks;
    m_nee_on = settings.connection_parts.cone_direct;
    m_glints_on = settings.connection_parts.glints;
    m_delta = m_azimuths && settings.delta_walks && settings.connection_parts.delta_walks;
    m_rates.delta_rate = std::clamp(settings.delta_rate, kMinDeltaRate, kMaxDeltaRate);
    m_rates.delta_chain_share = std::isnan(settings.delta_chain_share)
                                    ? 1.0
                                    : std::clamp(settings.delta_chain_share, kMinDeltaChainShare, 1.0);
    m_rates.drawn_chain_rate = std::isnan(settings.drawn_chain_rate)
                                   ? 1.0
                                   : std::clamp(settings.drawn_chain_rate, kMinDrawnChainRate, 1.0);
    m_rates.drawn_chain_rate_adapts = settings.adapt_drawn_chain_rate;
    m_rates.chain_length_um =
        std::isfinite(settings.chain_length_um) ? std::max(0.0, settings.chain_length_um) : 0.0;
    m_rates.chain_length_adapts = settings.adapt_chain_length;
    m_first_flake = m_delta && settings.first_flake_walks && !band.explicit_flakes.empty() &&
                    std::any_of(band.explicit_flakes[0].begin(), band.explicit_flakes[0].end(),
                                [](const LayerFlakes& lf) { return lf.groups != nullptr; });
    m_uniform_delta = m_delta && (!m_first_flake || otherDeltaStarts(stack));
    // The cone weights come from the adaptive model; without it the tables would stay unused.
    if (m_delta && m_adaptive && settings.chain_promise) buildChainPromise();
    m_rates.reverse_rate.assign(m_exits, std::clamp(settings.reverse_rate, kMinReverseRate, kMaxReverseRate));
    m_diagnostics = m_adaptive ? m_exits : 0;
    m_walk.max_events = settings.max_events;
    m_walk.roulette_weight = settings.roulette_weight;
    // What the connections and walks score, the histogram leaves out.
    m_walk.histogram_classes = settings.histogram_classes;
    if (m_connections) {
        m_walk.histogram_classes.beam_flake = false;
        m_walk.histogram_classes.smooth = false;
    }
    m_walk.reflected_beams = m_reverse && settings.reflected_beams;
    m_walk.top_images = m_reverse && settings.top_images;
    m_walk.flake_images = m_azimuths && settings.flake_images && settings.connection_parts.flake_images;
    m_walk.cone_direct = m_nee_on;
    HistogramOtherParts& other = m_walk.histogram_other;
    other = settings.histogram_other;
    if (m_reverse) other.smooth_first = false;
    if (m_delta) other.delta_chains = false;
    if (m_walk.reflected_beams) other.beam_flake_pigment = false;
    if (m_walk.top_images) other.beam_flake_top_pigment = false;
    if (m_walk.flake_images) {
        other.ends_pigment_flake = false;
        other.ends_pigment_top_flake = false;
    }
    m_walk.connections = m_connections;
    m_walk.connection_weight = 1.0 / m_connection_fraction;
    m_walk.split_branches = settings.explicit_flakes && settings.split_branches;
    m_walk.connection_roulette = settings.connection_roulette;
    m_walk.cavity_forms = settings.cavity_forms;
    m_walk.delta_chain_connections = settings.connection_parts.delta_chains;
    m_walk.forward_chain_connections =
        m_connections && settings.connection_parts.forward_chains &&
        std::any_of(band.explicit_flakes[0].begin(), band.explicit_flakes[0].end(),
                    [](const LayerFlakes& lf) { return lf.last_flake != nullptr; });
    buildViews(settings);
    if (m_azimuths) {
        m_azimuth_glints.resize(band.explicit_flakes.size());
        tbb::parallel_for(std::size_t{0}, band.explicit_flakes.size(), [&](std::size_t b) {
            m_azimuth_glints[b] = azimuthGlintSets(stack, band.explicit_flakes[b], m_v_in, m_bins);
        });
    }
}

// The delta walks' promise tables (chain_promise.h) in the frame of the
// unturned beam (every view turns beam and cones together): the cones'
// axes refracted into the first tiled layer's binder, the broadest
// orientation law of its flakes and their largest R near the normal
// (a paint with several tiled layers gets the first's: the promise only
// steers the roulette, which stays unbiased).
void JobRunner::buildChainPromise() {
    const PaintStack& stack = m_band.stack;
    const std::span<const LayerFlakes> layers = m_band.explicit_flakes.front();
    const auto tiled = std::find_if(stack.slices.begin(), stack.slices.end(), [&](const Slice& s) {
        return static_cast<std::size_t>(s.layer) < layers.size() &&
               layers[static_cast<std::size_t>(s.layer)].tile != nullptr;
    });
    const double lateral = std::hypot(m_v_in.x, m_v_in.y);
    if (tiled == stack.slices.end() || !(lateral > 0.0)) return;
    double kappa = std::numeric_limits<double>::infinity();
    double reflectance = 0.0;
    for (const FlakeKind& kind : layers[static_cast<std::size_t>(tiled->layer)].kinds) {
        if (!kind.orientation.isDelta()) kappa = std::min(kappa, kind.orientation.kappa());
        reflectance = std::max(reflectance, kind.R(0.9));
    }
    if (!std::isfinite(kappa)) return;  // mirror-like flakes: no density to weigh by
    const double bx = m_v_in.x / lateral;
    const double by = m_v_in.y / lateral;
    const double ratio = stack.ambient_n / tiled->n;
    std::vector<Vec3> cones;
    for (const HistogramBin& bin : m_bins) {
        const double wx = bin.wo.x * ratio;
        const double wy = bin.wo.y * ratio;
        const double z = std::sqrt(std::max(0.0, 1.0 - wx * wx - wy * wy));
        cones.push_back({wx * bx + wy * by, wy * bx - wx * by, z});
    }
    m_promise = ChainPromise(cones, kappa, reflectance);
}

// Explicit flakes: every tile is traced at tile_views azimuths of the
// incidence plane (McSettings): view m of batch b turns the beam, the
// exit cones and the projection's azimuth origin by psi = 2 pi (m + o_b) / M
// about the normal (o_b a fixed random offset per batch), so the tile is
// seen as if turned by -psi. Otherwise one view, not turned.
void JobRunner::buildViews(const McSettings& settings) {
    const bool turn = settings.explicit_flakes && !m_band.explicit_flakes.empty();
    m_view_count = turn ? static_cast<std::size_t>(std::max(1, settings.tile_views)) : 1;
    const std::size_t batch_count = turn ? m_band.explicit_flakes.size() : 1;
    m_views.assign(batch_count, std::vector<View>(m_view_count));
    tbb::parallel_for(std::size_t{0}, batch_count * m_view_count, [&](std::size_t index) {
        const std::size_t b = index / m_view_count;
        const std::size_t m = index % m_view_count;
        std::uint64_t key = settings.seed ^ (0x746f726e ^ b);  // "torn"
        const double offset =
            m_view_count > 1 ? static_cast<double>(splitMix64(key) >> 11U) * 0x1.0p-53 : 0.0;
        const double psi =
            2.0 * std::numbers::pi * (static_cast<double>(m) + offset) / static_cast<double>(m_view_count);
        const double c = std::cos(psi);
        const double sn = std::sin(psi);
        const auto turned = [c, sn](const Vec3& a) {
            return Vec3{c * a.x - sn * a.y, sn * a.x + c * a.y, a.z};
        };
        View& view = m_views[b][m];
        view.v_in = turned(m_v_in);
        view.bins = m_bins;
        for (auto& bin : view.bins) bin.wo = turned(bin.wo);
        view.cells = m_cells;
        const Vec3 in = turned({m_cells.cos_in, m_cells.sin_in, 0.0});
        view.cells.cos_in = in.x;
        view.cells.sin_in = in.y;
        if (m_connections && !settings.glint_azimuths)
            view.glints = glintSets(m_band.stack, m_band.explicit_flakes[b], view.v_in, view.bins);
    });
}

bool JobRunner::adapt(const Sums& total) {
    if (!m_adaptive || total.paths < kPathsToAdapt || total.cones.size() != m_exits) return false;
    const RateFit fit = adaptRates(total, estimateEntries(), m_reverse, m_delta, m_rates);
    m_account = fit.account;
    const std::vector<double> needs = coneNeeds(total);
    learnCavityFormWeights(total, needs);
    // The last-flake connections' cone draw, p_k ~ sqrt(need_k) times the
    // flight's kernel: each cone's connections then carry the stop rule's
    // variance-optimal share, sqrt(need_k E[g_k^2]) (the kernel standing for
    // the root of the mean square g_k^2 of a flight's score into cone k).
    if (m_settings.kernel_chain_cones) {
        if (!needs.empty()) {
            m_chain_cone_scale.resize(needs.size());
            for (std::size_t k = 0; k < needs.size(); ++k) m_chain_cone_scale[k] = std::sqrt(needs[k]);
        }
    }
    if (m_first_flake) learnFirstFlakeProposal(total, fit.f2);
    weighPromiseCones(total, fit.delta_variance, fit.f2);
    return true;
}

double JobRunner::forecastVarianceRatio(const Sums& total) const {
    if (!m_adaptive || total.paths < kPathsToAdapt || total.cones.size() != m_exits)
        return std::numeric_limits<double>::quiet_NaN();
    ConeRates rates = m_rates;
    const RateFit fit = adaptRates(total, estimateEntries(), m_reverse, m_delta, rates);
    return fit.rel_variance / fit.previous_rel_variance;  // NaN or inf where the model has no variance
}

// The drawn cavity chains' weights (CavityFormWeights): each form's draw in
// proportion to the root of its mean square, the variance-optimal share of
// a one-of-many draw, with the cones weighed by the stop rule's need: w_k =
// r_k / f_k^2, r_k the cone's relative variance per path over the largest,
// so the mean square is that of the relative errors, the worst cone's most.
// A form never drawn keeps the uniform share alone.
std::vector<double> JobRunner::coneNeeds(const Sums& total) const {
    if (total.paths < 2 || total.mean.size() < kFirstExit + m_exits) return {};
    std::vector<double> w(m_exits, 0.0);
    double r_max = 0.0;
    for (std::size_t k = 0; k < m_exits; ++k) {
        const double f = total.mean[kFirstExit + k];
        if (!(f > 0.0)) continue;
        w[k] = total.m2[kFirstExit + k] / static_cast<double>(total.paths - 1) / (f * f);
        r_max = std::max(r_max, w[k]);
    }
    if (!(r_max > 0.0)) return {};
    for (std::size_t k = 0; k < m_exits; ++k) {
        const double f = total.mean[kFirstExit + k];
        w[k] = f > 0.0 ? w[k] / (r_max * f * f) : 0.0;
    }
    return w;
}

void JobRunner::learnCavityFormWeights(const Sums& total, std::span<const double> w) {
    const CavityFormLearning& learned = total.form_learning;
    if (total.paths < 2 || learned.m2_over_p.size() < kCavityFormSlots * m_exits) return;
    if (w.empty()) return;
    bool any = false;
    for (std::size_t i = 0; i < m_form_weights.size(); ++i) {
        const double flights = learned.available[i];
        double m2 = 0.0;
        for (std::size_t k = 0; k < m_exits; ++k) m2 += w[k] * learned.m2_over_p[i * m_exits + k];
        m_form_weights[i] = flights > 0.0 ? std::sqrt(m2 / flights) : 0.0;
        any = any || m_form_weights[i] > 0.0;
    }
    m_form_weights_learned = any;
}

// The promise's cone weights (chain_promise.h): a chain into cone k is
// worth its share of f_k (the stop rule's measure) times the cone's need
// of the delta walks, the relative variance they leave in it over the
// largest such: c_k = (f_min / f_k) (v_k / v_max), v_k = Var_delta,k / f_k^2.
// (With f_min / f_k alone the near-specular cones, whose delta part is tiny,
// kept most branches alive.)
void JobRunner::weighPromiseCones(const Sums& total, const std::vector<double>& delta_variance,
                                  const std::vector<double>& f2) {
    if (m_promise.empty()) return;
    double f_min = std::numeric_limits<double>::infinity();
    double v_max = 0.0;
    for (std::size_t k = 0; k < m_exits; ++k) {
        const double f = total.mean[kFirstExit + k];
        if (f > 0.0) f_min = std::min(f_min, f);
        if (f2[k] > 0.0) v_max = std::max(v_max, delta_variance[k] / f2[k]);
    }
    if (!std::isfinite(f_min) || !(v_max > 0.0)) return;
    std::vector<double> weights(m_exits, 0.0);
    for (std::size_t k = 0; k < m_exits; ++k) {
        const double f = total.mean[kFirstExit + k];
        if (f > 0.0) weights[k] = f_min / f * (delta_variance[k] / f2[k]) / v_max;
    }
    m_promise.setConeWeights(weights);
}

// The first-flake walks' group weights from every walk so far (first_flake.h):
// P_G proportional to A_G rho_key is variance-optimal for the sum of the
// cones' relative variances (the flop cones, whose delta part is largest,
// weigh most) at rho_key^2 = E[sum_k (f_k P_G / A_G)^2 / f_k^2 | key]. A
// key holds few hits (a few hundred over hundreds of keys at the demo's
// flop), so its mean square is shrunk towards that of all keys with the
// weight of kFirstFlakePrior draws: unmeasured keys stay area-proportional.
// (Without the shrinkage the learned weights follow single hits.)
void JobRunner::learnFirstFlakeProposal(const Sums& total, const std::vector<double>& f2) {
    const std::size_t keys = total.first_count.size();
    std::vector<double> s(keys, 0.0);
    double s_all = 0.0;
    double n_all = 0.0;
    for (std::size_t key = 0; key < keys; ++key) {
        for (std::size_t k = 0; k < m_exits; ++k)
            if (f2[k] > 0.0 && (key + 1) * m_exits <= total.first_s2.size())
                s[key] += total.first_s2[key * m_exits + k] / f2[k];
        s_all += s[key];
        n_all += total.first_count[key];
    }
    if (!(s_all > 0.0) || !(n_all > 0.0)) return;
    const double mean_all = s_all / n_all;
    m_first_proposal.h.assign(keys, 0.0);
    for (std::size_t key = 0; key < keys; ++key)
        m_first_proposal.h[key] =
            std::sqrt((s[key] + kFirstFlakePrior * mean_all) / (total.first_count[key] + kFirstFlakePrior));
    m_first_proposal.rho_default = std::sqrt(mean_all);
}

}  // namespace paintlab::mc
