#pragma once
// Roulette by promise for the delta-chain walks (McSettings::chain_promise;
// mc_walk.h, traceDeltaChains). A delta walk's score is a chain of mirror
// reflections that ends in an exit cone, and most branches of its split tree
// head where no next reflection can send them: a scratch log of the
// pearlescent demo at 437 nm (1.05 M walks, 12 M branches) found half of the
// downward branches after the beam's first change with D(h) < 3.4e-3 of its
// peak for the half-vector h that would turn them into 45as110, where the
// last downward branch of every scoring chain had D(h) > 1.7e-4 and 90 % of
// them > 0.13 (docs/PERFORMANCE.md, "Roulette by promise").
//
// So each new branch (after a reflection, or a split's passed share) gets a
// promise: downward, sum_k c_k D(h_k) / D(1), the orientation law at the
// half-vector that mirrors it into cone k; upward and outside every cone,
// R sum_k c_k E_B[D(h_k(reflect(d, n_B))) / D(1)] over the normal n_B of
// the flake whose underside would turn it down (n_B from D weighted by
// |d.n_B|); upward into a cone, no roulette. The cone weights c_k =
// (f_min / f_k) (v_k / v_max) weigh a chain by its share of f_k and the cone
// by its need of the delta walks, v_k the relative variance they leave in it
// (JobRunner::weighPromiseCones). The branch survives with
// q = clamp(w promise / threshold, floor, 1) and carries w / q: unbiased for
// any promise (weight-window roulette, e.g. Vorba and Krivanek 2016,
// "Adjoint-driven Russian roulette and splitting"), so the tables may be
// coarse. Directions are binned in the beam's frame (x along the beam's
// lateral travel), by their lateral components on a square grid over
// [-1, 1]^2: kDownBins wide for downward directions, kUpBins for upward
// ones (their promise is D averaged over a flake's tilt, so smoother and
// costlier to tabulate). No trigonometry in the lookup: with an atan2 of
// the azimuth the lookup was ~5 % of a run; building the tables is 0.2 %
// (perf, the demo's stop-rule run).

#include "mc_stack.h"

#include <span>
#include <vector>

namespace paintlab::mc {

class ChainPromise {
public:
    static constexpr int kDownBins = 64;
    static constexpr int kUpBins = 32;

    ChainPromise() = default;
    // cones_in_film: each cone's axis in the flakes' binder (unit, upward),
    // in the beam's frame (x along the beam's lateral travel); kappa: the
    // broadest flake orientation law's (FlakeOrientation::kappa);
    // reflectance: a typical flake R at this wavelength (the upward tables' factor).
    ChainPromise(std::span<const Vec3> cones_in_film, double kappa, double reflectance);

    // Weighs cone k by weights[k] (>= 0; the combined table is their sum).
    void setConeWeights(std::span<const double> weights);
    bool empty() const { return m_per_cone.empty(); }   // no tables (off)
    bool ready() const { return !m_combined.empty(); }  // tables and cone weights

    // The promise of direction d (any unit vector) given the beam's lateral
    // travel direction (bx, by) (unit).
    double at(const Vec3& d, double bx, double by) const;

private:
    // [cone][cell]: the downward grid's cells (iy kDownBins + ix), then the upward grid's.
    std::vector<std::vector<float>> m_per_cone;
    std::vector<float> m_combined;  // [cell]
};

}  // namespace paintlab::mc
