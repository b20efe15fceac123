#pragma once
// BRDF samples of a measured material on the BRDF-sample contract of
// `paintlab-cli db import` and `fit --measurement` (measurement_files.h):
// CSV columns theta_i_deg, phi_i_deg, theta_o_deg, phi_o_deg, R, G, B
// (linear sRGB, 1/sr).
//
// The directions (sampleDirections) are deterministic for a seed and
// stratified over incidence 0-80°, in four groups:
//   - the six multi-angle geometries (45as-15 ... 45as110, multiangle.h), each
//     exactly and at 4 neighbours 2° away in and across the plane;
//   - the in-plane flop: views in the plane of incidence on both sides;
//   - the specular lobe: views within 20° of the mirror direction, denser
//     towards it (angle 20° u²);
//   - the hemisphere: views cosine-distributed (projected solid angle).
// Views are kept at or above 10° elevation (θo <= 80°): the neural fits
// weighted their training by cos θi, and grazing values are the least
// reliable (the data's README). Angles are rounded to 0.01°, so that the file
// holds exactly the geometry at which the values were computed.

#include "paintlab/measured_brdf/rgb_brdf.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace paintlab::measured {

struct SampleDirection {
    double theta_i_deg = 0.0;
    double phi_i_deg = 0.0;
    double theta_o_deg = 0.0;
    double phi_o_deg = 0.0;
    Direction wi() const;
    Direction wo() const;
};

inline constexpr double kMaxThetaDeg = 80.0;
inline constexpr std::size_t kDefaultSampleCount = 2000;
inline constexpr std::uint64_t kDefaultSampleSeed = 20261205;

// count >= 100 directions (the multi-angle group alone is 30). Throws
// InputError("<argument>", "count") below that.
std::vector<SampleDirection> sampleDirections(std::size_t count = kDefaultSampleCount,
                                              std::uint64_t seed = kDefaultSampleSeed);

// The contract's CSV of brdf at the directions (header and one row each).
std::string samplesCsv(const RgbBrdf& brdf, const std::vector<SampleDirection>& directions);

// RMS over the directions and the three channels of the cosine-weighted log
// residual (rgb_brdf.h) of model against reference: the fit's BRDF error.
double cosineLogRms(const RgbBrdf& model, const RgbBrdf& reference,
                    const std::vector<SampleDirection>& directions);

}  // namespace paintlab::measured
