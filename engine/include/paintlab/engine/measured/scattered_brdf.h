#pragma once
// A measured BRDF given as scattered samples (a goniophotometer's
// (wi, wo, f) triples, or bins of a MERL table), evaluated anywhere by
// interpolation, so that it can be shaded like a model BRDF (the Match dock's
// split view of measured against fitted, issue 28).
//
// Isotropic: each direction pair is reduced to Rusinkiewicz's half/difference
// angles (S. Rusinkiewicz, "A new change of variables for efficient BRDF
// representation", EGWR 1998): theta_h (half vector from the normal),
// theta_d and phi_d (the light direction in the half vector's frame). With
// reciprocity and isotropy f depends on phi_d only modulo 180 degrees and up
// to its sign, so phi_d is folded to [0, 90] degrees. A pair is the point
// (theta_h, d) with d the unit difference vector folded to that quarter; the
// distance between pairs is the Euclidean distance of those points (radians
// for small differences; phi_d counts in proportion to sin theta_d, where it
// matters).
//
// eval() is inverse-distance weighting (Shepard, power 2) of the k nearest
// samples. It reproduces a sample exactly at its own geometry, never leaves
// the range of its neighbours' values (no overshoot on a specular peak), and
// is as good as the samples are dense: the error where every query has
// samples within a few degrees is measured in tests/engine/measured.
// density() says whether a set of queries (what a renderer will ask for) is
// covered well enough to shade with.
//
// Brute-force neighbour search: O(samples) per query, ~20 µs for 4,000
// samples; a renderer calls it from several threads (const, no state).

#include "paintlab/engine/brdf.h"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace paintlab::measured {

// Half/difference angles in radians; phi_d folded to [0, pi/2].
struct HalfDifference {
    double theta_h = 0.0;
    double theta_d = 0.0;
    double phi_d = 0.0;
};
// Directions need not be normalised; both above the horizon (z > 0).
HalfDifference halfDifference(const Direction& wi, const Direction& wo) noexcept;

struct ScatteredSample {
    Direction wi;
    Direction wo;
    std::vector<double> values;  // f in 1/sr, one per channel
};

struct ScatteredBrdfSettings {
    std::size_t neighbours = 6;  // k of the inverse-distance weighting
};

class ScatteredBrdf {
public:
    // Throws InputError(source, "samples[i]...") if there are no samples, a
    // sample has not `channels` values, a value is negative or not finite, or
    // a direction is at or below the horizon.
    ScatteredBrdf(std::span<const ScatteredSample> samples, std::size_t channels, const std::string& source,
                  ScatteredBrdfSettings settings = {});

    std::size_t channels() const { return m_channels; }
    std::size_t size() const { return m_points.size(); }

    // f(wi, wo) per channel into out (out.size() == channels()). Never throws;
    // directions at or below the horizon give 0.
    void eval(const Direction& wi, const Direction& wo, std::span<double> out) const noexcept;
    // The distance (above) from (wi, wo) to the nearest sample; infinite
    // below the horizon.
    double nearestDistance(const Direction& wi, const Direction& wo) const noexcept;

private:
    struct Point {
        double theta_h, dx, dy, dz;
    };
    static Point pointOf(const HalfDifference& hd) noexcept;
    static double distance2(const Point& a, const Point& b) noexcept;

    std::size_t m_channels = 0;
    ScatteredBrdfSettings m_settings;
    std::vector<Point> m_points;
    std::vector<double> m_values;  // size() x channels()
};

// Whether a measurement is dense enough to shade the direction pairs a
// renderer needs: at least min_samples samples, and at least min_covered of
// the queries have a sample within radius (the distance above). The
// defaults: 8° (0.14 rad) is about the width of a paint's specular peak at
// its half maximum (a clear coat's gloss lobe over a rough basecoat), so
// nothing finer than what the samples resolve is shown as measured; 90 % of
// the pixels lets a sphere's grazing rim go unmeasured, as
// goniophotometers rarely reach it.
struct DensityCriterion {
    std::size_t min_samples = 100;
    double radius_rad = 0.14;
    double min_covered = 0.90;
};

struct DirectionPair {
    Direction wi;
    Direction wo;
};

struct Density {
    bool dense = false;
    std::size_t samples = 0;
    double covered = 0.0;  // fraction of the queries within the radius
    std::string reason;    // why not (empty when dense), with the figures
};

Density density(const ScatteredBrdf& brdf, std::span<const DirectionPair> queries,
                const DensityCriterion& criterion = {});

}  // namespace paintlab::measured
