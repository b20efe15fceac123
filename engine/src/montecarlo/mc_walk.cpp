#include "mc_walk.h"

#include "first_flake.h"
#include "mc_walker.h"

#include <cmath>

namespace paintlab::mc {

PathOutcome tracePath(const PathContext& context, Vec3 v, double weight, double x, double y, PathRng& rng,
                      std::span<double> f_out, PathRng* connection_rng) {
    const bool connect = context.settings.connections && connection_rng != nullptr &&
                         !context.explicit_flakes.empty() && !context.bins.empty();
    Walker walker(context.stack, context.explicit_flakes, context.settings, rng, v, weight, x, y);
    walker.chains = context.chains;
    walker.bins = context.bins;
    walker.fourier = context.fourier;
    walker.connection_rng = connect ? connection_rng : nullptr;
    walker.brdf_out = f_out;
    walker.nee_weights = context.nee_weights;
    walker.nee_out = context.nee_out;
    walker.nee_boost = context.nee_boost;
    if (walker.chainRecording()) walker.markVertex();  // the entry point
    const double escaped = walker.run() + walker.tally.escaped_extra;
    if (connect && !context.glints.empty())
        scoreGlints(context.stack, context.explicit_flakes, context.glints, context.bins,
                    context.settings.connection_weight, *connection_rng, f_out);
    const WalkTally& t = walker.tally;
    return {escaped,    t.transmitted,  t.events,      t.rays,
            t.nee_rays, t.nee_attempts, t.image_calls, t.image_rays};
}

namespace {

// What the delta-chain walks score: class Other's chains without a smooth vertex (delta_chains).
WalkSettings deltaChainSettings(const WalkSettings& settings) {
    WalkSettings delta = settings;
    delta.histogram_classes = HistogramClasses::none();
    delta.histogram_classes.other = true;
    delta.histogram_other = HistogramOtherParts::none();
    delta.histogram_other.delta_chains = true;
    return delta;
}

// A walk without collisions (Walker::Mode::DeltaChain) from (x, y, depth) in slice j.
Walker deltaWalker(const PathContext& context, const WalkSettings& settings, PathRng& rng,
                   std::span<double> f_out, const Vec3& v, double weight, double x, double y, std::size_t j,
                   double depth, PathClass path_class) {
    Walker walker(context.stack, context.explicit_flakes, settings, rng, v, weight, x, y);
    walker.bins = context.bins;
    walker.brdf_out = f_out;
    walker.chain_out = context.chain_out;
    walker.form_learning = context.form_learning;
    walker.length_learning = context.length_learning;
    walker.j = j;
    walker.depth = depth;
    walker.history.path_class = path_class;
    walker.mode = Walker::Mode::DeltaChain;
    walker.ux = x;
    walker.uy = y;
    return walker;
}

}  // namespace

PathOutcome traceDeltaChains(const PathContext& context, Vec3 v, double weight, double x, double y,
                             PathRng& rng, std::span<double> f_out) {
    const WalkSettings settings = deltaChainSettings(context.settings);
    Walker walker = deltaWalker(context, settings, rng, f_out, v, weight, x, y, 0, 0.0, PathClass::Beam);
    const double lateral = std::hypot(v.x, v.y);
    if (lateral > 0.0) {
        walker.beam_x = v.x / lateral;
        walker.beam_y = v.y / lateral;
    }
    walker.promise_weight = settings.promise_threshold * weight;
    walker.markVertex();  // the entry point
    const double escaped = walker.run() + walker.tally.escaped_extra;
    return {escaped, walker.tally.transmitted, walker.tally.events, walker.tally.rays,
            0,       walker.tally.nee_attempts};
}

PathOutcome traceFromFirstFlake(const PathContext& context, const Vec3& v_top, double weight,
                                const FirstFlakeDraw& draw, PathRng& rng, std::span<double> f_out) {
    if (draw.layer < 0 || static_cast<std::size_t>(draw.layer) >= context.explicit_flakes.size()) return {};
    const PaintStack& stack = context.stack;
    const LayerFlakes& lf = context.explicit_flakes[static_cast<std::size_t>(draw.layer)];
    const PlacedFlake& flake = lf.tile->flakes()[draw.flake];
    const double depth = -draw.point.z;
    const std::size_t j = sliceAt(stack, draw.layer, depth);
    if (j == stack.slices.size()) return {};
    // The beam in slice j: refracted at every index step above it.
    Vec3 v = v_top;
    for (std::size_t i = 0; i < j; ++i) {
        const double n_from = stack.slices[i].n;
        const double n_to = stack.slices[i + 1].n;
        Vec3 below;
        if (std::abs(n_from - n_to) < 1e-12) continue;
        if (!refractPlanar(v, n_from, n_to, below)) return {};
        v = below;
    }
    const double vn = dot(v, flake.normal);
    const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
    if (!(R > 0.0) || !(std::abs(v.z) > 1e-12)) return {};
    PathOutcome outcome;
    const double t_in = straightToTop(stack, context.explicit_flakes, j, depth, draw.point.x, draw.point.y,
                                      {-v.x, -v.y, -v.z}, &outcome.rays)
                            .T;
    if (!(t_in > 0.0)) return outcome;
    const double L = lf.tile->sideUm();
    const double start =
        weight * t_in * R * draw.area_over_probability * std::abs(vn) / (L * L * std::abs(v.z));
    WalkSettings settings = deltaChainSettings(context.settings);
    settings.roulette_weight *= draw.natural_over_probability;
    const Vec3 r{v.x - 2.0 * vn * flake.normal.x, v.y - 2.0 * vn * flake.normal.y,
                 v.z - 2.0 * vn * flake.normal.z};
    Walker walker = deltaWalker(context, settings, rng, f_out, r, start, draw.point.x, draw.point.y, j, depth,
                                PathClass::BeamFlake);
    walker.splits = 1;  // as after the uniform walk's split at this flake
    // The chain's flakes met before its first are not known here (the beam's
    // leg down to it is traced by straightToTop): the walk scores all of its
    // escapes itself (last_flake.h).
    walker.chain_connections = false;
    if (!walker.roulette()) return outcome;
    outcome.escaped = walker.run() + walker.tally.escaped_extra;
    outcome.transmitted = walker.tally.transmitted;
    outcome.events = walker.tally.events;
    outcome.rays += walker.tally.rays;
    return outcome;
}

ReverseOutcome traceReversePath(const PathContext& context, Vec3 v, double weight, double x, double y,
                                const Vec3& target, PathRng& rng, PathRng& connection_rng) {
    WalkSettings settings = context.settings;
    settings.histogram_classes = HistogramClasses::none();
    Walker walker(context.stack, context.explicit_flakes, settings, rng, v, weight, x, y);
    walker.connection_rng = &connection_rng;
    walker.mode = Walker::Mode::Reverse;
    walker.reverse_target = target;
    walker.run();
    const WalkTally& t = walker.tally;
    return {t.reverse_score, t.events + t.rays, t.nee_rays + t.nee_attempts, t.image_calls, t.image_rays};
}

}  // namespace paintlab::mc
