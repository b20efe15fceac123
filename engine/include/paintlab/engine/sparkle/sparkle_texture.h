#pragma once
// The deterministic random sparkle texture (issue 7): per surface element, a
// draw of the glints whose statistics sparkle.h gives, as a zero-mean
// modulation added to the relit BRDF:
//
//   L = L_brdf + E mu_i V sum_t f_t (X_t - 1),    E[X_t] = 1 exactly,
//
// so the mean of the textured radiance is the BRDF's radiance by
// construction (energy is moved between elements, not created), whatever
// the draw. X_t = S_t / E[S_t] is term t's compound Poisson sum of glint
// weights: N ~ Poisson(Lambda_t) flakes at depths uniform in the slice, each
// weighted by w(z) / (Lambda_t E[w]). When Lambda_t > 256 the sum is drawn
// from the gamma distribution of the same mean and variance (eq. (4)):
// non-negative and skewed like the sum, a few hundred times cheaper.
//
// The random numbers are keyed by the surface cell (power-of-two side near
// the element's), the term (layer, component, slice) and the half vector's
// tilt binned near the window's width: moving light or view reaches other
// flakes, while recipe, exposure or camera changes keep the draws and change
// only the Poisson means. After Jakob et al., "Discrete stochastic
// microfacet models", SIGGRAPH 2014, and Zirr and Kaplanyan, "Real-time
// rendering of procedural multiscale materials", I3D 2016.

#include "paintlab/engine/sparkle/sparkle.h"

#include <cstdint>
#include <span>
#include <vector>

namespace paintlab {

// The key of the surface cell around a position (µm) for an element of this
// side (µm): side 2^floor(log2(element_side)), cell floor(p / side), hashed
// with the seed. Never throws (a non-finite input gives key of cell 0).
std::uint64_t sparkleCellKey(double x_um, double y_um, double z_um, double element_side_um,
                             std::uint64_t seed = 0);

// X_t - 1 for every term of `stats` at the cell `cell_key` (modulation.size()
// must equal stats.terms.size(); extra entries are left alone). Never throws.
void drawSparkle(const SparkleStats& stats, std::uint64_t cell_key, std::span<double> modulation);

// sum_t f_t (X_t - 1), per band (1/sr): the BRDF's zero-mean sparkle part;
// times E mu_i V it is radiance.
std::vector<double> sparkleBrdfModulation(const SparkleStats& stats, std::uint64_t cell_key);

}  // namespace paintlab
