#pragma once
// Explicit flakes of one layer: a laterally periodic tile of side L (µm)
// filled with flat polygons (regular 16-gons of the flake's area by default,
// or exact disks) with
// sampled diameter (a lognormal about the mean when the recipe gives a
// spread), position (uniform laterally, depth from the concentration profile)
// and normal (FlakeOrientation), intersected with Embree (user geometry: one
// primitive per flake, the plane and polygon tested in double). Flakes that cross
// the tile's sides are repeated one period over, so a ray inside the tile
// sees everything it can hit there; the walk wraps rays at the sides.
// The only file of the engine that includes Embree (with flake_tile.cpp).

#include "flake_polygon.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

namespace paintlab::mc {

// Ray offset from the flake a ray leaves (µm): the geometry is float.
constexpr double kTileEpsilonUm = 1e-3;

// What the tile needs of one kind of flake (the optics come from FlakeKind per wavelength).
struct FlakeGeometry {
    double area_density_per_um = 0.0;  // mean over the layer
    double diameter_um = 0.0;          // mean
    double spread_deg = 0.0;
    const DepthProfile* profile = nullptr;  // null: uniform in depth
    // Standard deviation of the diameter (µm): each flake's diameter is drawn
    // from a lognormal with mean diameter_um and this sd (cut where 3e-7 of it
    // lies beyond); 0: every flake diameter_um across.
    double diameter_sd_um = 0.0;
};

// A kind's flake diameters (FlakeGeometry::diameter_sd_um): a lognormal with
// the mean diameter and that standard deviation, cut at 5 of its log-space
// standard deviations above the log mean (3e-7 of the draws: a cut at mean +
// 4 sd removed 0.3-0.5 % of them at coefficients of variation 1/3-1/2, the
// largest, and with them 2-5 % of the flakes' area), or every flake the mean
// size. Drawn from their own stream, so that a spread of 0 leaves every other
// draw of the tile as it was.
class DiameterLaw {
public:
    explicit DiameterLaw(const FlakeGeometry& kind) : m_mean(kind.diameter_um), m_cap(kind.diameter_um) {
        const double sd = std::max(0.0, kind.diameter_sd_um);
        if (sd > 0.0 && m_mean > 0.0) {
            m_log_variance = std::log1p((sd / m_mean) * (sd / m_mean));
            m_log_mean = std::log(m_mean) - 0.5 * m_log_variance;
            m_cap = std::exp(m_log_mean + 5.0 * std::sqrt(m_log_variance));
        }
        // E[d^2] = mean^2 + sd^2 (the cut's share is below the flake count's rounding).
        m_mean_area = 0.25 * std::numbers::pi * (m_mean * m_mean + sd * sd);
    }
    double meanAreaUm2() const { return m_mean_area; }
    double largestUm() const { return m_cap; }
    double sample(PathRng& rng) const {
        if (!(m_log_variance > 0.0)) return m_mean;
        for (;;) {
            // Box-Muller; 1 - u keeps the logarithm finite.
            const double z = std::sqrt(-2.0 * std::log(1.0 - rng.uniform())) *
                             std::cos(2.0 * std::numbers::pi * rng.uniform());
            const double d = std::exp(m_log_mean + std::sqrt(m_log_variance) * z);
            if (d <= m_cap) return d;
        }
    }

private:
    double m_mean;
    double m_cap;
    double m_log_mean = 0.0;
    double m_log_variance = 0.0;
    double m_mean_area = 0.0;
};

// The flake kinds of a layer in the order of layerFlakeKinds (mc_stack.h):
// mirror flakes, then interference flakes, each present one in component order.
std::vector<FlakeGeometry> layerFlakeGeometries(const Layer& layer);

// A placed flake as a thickness-less disk: its centre (z = minus the depth,
// µm), unit normal and the radius that encloses its polygon.
struct PlacedFlake {
    Vec3 centre;
    Vec3 normal;
    double radius_um = 0.0;
    int kind = 0;
    double rotation = 0.0;  // of the polygon's first vertex in the flake's plane (radians)
};

// Whether two thickness-less disks share a point: parallel ones only when
// coplanar and closer than the sum of the radii; otherwise each disk cuts
// the line where the planes meet in a chord, and the disks intersect when
// the chords overlap. No periodic images: the caller shifts b.
bool disksIntersect(const PlacedFlake& a, const PlacedFlake& b);

struct FlakeHit {
    double t = 0.0;
    Vec3 normal;              // unit, either side
    int kind = -1;            // index into the layer's FlakeGeometry list; -1: no hit
    std::int64_t flake = -1;  // index into FlakeTile::flakes() (any periodic copy of it)
};

class FlakeTile {
public:
    // Throws Error if Embree fails. target_flakes sets the tile size (at least
    // two diameters of the largest flake); max_flakes caps the count. With
    // reject_overlaps a flake that intersects one already placed (periodic
    // images included; disks of the polygon's circumradius, so the traced
    // polygons cannot intersect either) is moved to a new lateral position
    // (its depth and normal stay, so the depth profile and the
    // orientation distribution are kept); InputError if a flake finds no free
    // place in 100,000 draws (the concentration is too high for flat flakes).
    // `stop`, if given, is polled between flake kinds and by Embree's BVH
    // build (most of the time): once it is true the constructor throws
    // Error "cancelled" within a fraction of the build. polygon_sides: the
    // flakes' shape, regular polygons of the disk's area with this many
    // sides (at least 3), or 0 for exact disks; InputError otherwise.
    FlakeTile(const std::vector<FlakeGeometry>& kinds, double top_um, double bottom_um, std::uint64_t seed,
              int target_flakes, int max_flakes, bool reject_overlaps = false,
              const std::atomic<bool>* stop = nullptr, int polygon_sides = kFlakePolygonSides);
    ~FlakeTile();
    FlakeTile(const FlakeTile&) = delete;
    FlakeTile& operator=(const FlakeTile&) = delete;
    FlakeTile(FlakeTile&&) noexcept;
    FlakeTile& operator=(FlakeTile&&) noexcept;

    double sideUm() const { return m_side_um; }
    int polygonSides() const { return m_sides; }  // 0: disks
    std::int64_t flakeCount() const { return m_flakes; }
    // Every flake once (centres inside the tile; the copies over its sides are not listed).
    const std::vector<PlacedFlake>& flakes() const { return m_placed; }
    // Area of flake i's polygon or disk (µm^2; the disk's area of its diameter).
    double flakeAreaUm2(std::size_t i) const;
    // A point of flake i's polygon, uniform over its area for u1, u2, u3
    // uniform in [0, 1) (a triangle of the fan, then a point in it; a disk:
    // the azimuth from u1, the radius from u2).
    Vec3 pointOnFlake(std::size_t i, double u1, double u2, double u3) const;
    // Whether a point of flake i's plane, given relative to its centre (or to
    // that of a periodic copy), lies on its polygon.
    bool onFlake(std::size_t i, const Vec3& relative) const;
    // Nearest flake along origin + t dir, t in (t_near, t_far). Thread-safe.
    FlakeHit intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    double m_side_um = 0.0;
    int m_sides = kFlakePolygonSides;
    std::int64_t m_flakes = 0;
    std::vector<PlacedFlake> m_placed;
};

}  // namespace paintlab::mc
