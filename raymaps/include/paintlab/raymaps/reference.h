#pragma once
// The brute-force reference of a relit image (docs/RAYMAPS.md, "Reference"):
// a path tracer of the same scene in which the paint is shaded with the same
// RGB BRDF as relight (RelightTables' f_rgb and clear-coat term) at every
// bounce, with no ray-map approximation (no moments, no proxy, no single
// frame per pixel). Tests and docs only: it is slow by design.

#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"

namespace paintlab::raymaps {

struct ReferenceSettings {
    int samples_per_pixel = 64;
    int max_depth = 6;  // scattering path vertices (mirror and glass bounces not counted)
    std::uint64_t seed = 7;
};

struct ReferenceImage {
    RgbImage mean;
    // Per pixel and channel: the variance of the mean (sample variance / n),
    // for statistical comparisons.
    std::vector<float> variance_of_mean;
};

// Throws InputError for bad settings or scene files, Error("cancelled").
ReferenceImage renderReference(const Scene& scene, const RelightTables& tables,
                               const ReferenceSettings& settings, const RayMapProgress& progress = {});

}  // namespace paintlab::raymaps
