#include "flake_tile.h"

#include "flake_polygon.h"

#include "mc_random.h"

#include "paintlab/engine/error.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <variant>

namespace paintlab::mc {

namespace {

void onEmbreeError(void* user, RTCError /*code*/, const char* message) {
    auto* text = static_cast<std::string*>(user);
    if (text->empty()) *text = message != nullptr ? message : "unknown Embree error";
}

// Relative depth in [0, 1] drawn from a piecewise-linear profile by rejection.
double sampleDepth(const DepthProfile* profile, PathRng& rng) {
    if (profile == nullptr) return rng.uniform();
    const double peak = *std::max_element(profile->weight.begin(), profile->weight.end());
    if (!(peak > 0.0)) return rng.uniform();
    for (int tries = 0; tries < 100000; ++tries) {
        const double z = rng.uniform();
        if (rng.uniform() * peak < profile->weightAt(z)) return z;
    }
    return rng.uniform();
}

// Van der Corput radical inverse of i in the given base (Halton sequence).
double radicalInverse(std::uint64_t i, std::uint64_t base) {
    double inverse = 0.0;
    double scale = 1.0 / static_cast<double>(base);
    for (; i > 0; i /= base, scale /= static_cast<double>(base))
        inverse += static_cast<double>(i % base) * scale;
    return inverse;
}

// Lateral positions a flake may try before its layer counts as too crowded
// to reject overlaps. The silver metallic demo (18 µm flakes, 12 degrees,
// ~2 flake layers in 15 µm) needs up to ~1,800 for its most tilted flakes
// (10 in 320,000 need more than 1,000, the cap before; the count needed falls
// off about fourfold per 500 more), so 100,000 leaves room; a truly
// impossible layer costs one flake 100,000 tests of its few neighbours.
constexpr int kPlacementTries = 100000;

// Placed flakes binned by lateral position (cells at least one flake
// diameter wide, wrapping), for the overlap test.
class LateralGrid {
public:
    LateralGrid(double side_um, double max_radius_um)
        : m_side(side_um),
          m_cells(static_cast<int>(std::clamp(side_um / (2.0 * max_radius_um), 1.0, double(kMaxCells)))) {
        m_bins.resize(static_cast<std::size_t>(m_cells) * static_cast<std::size_t>(m_cells));
    }

    void add(const PlacedFlake& flake, std::size_t index) { m_bins[bin(flake.centre)].push_back(index); }

    // Whether `flake` intersects a placed one, each at its nearest periodic image.
    bool collides(const PlacedFlake& flake, const std::vector<PlacedFlake>& placed) const {
        const int ci = cell(flake.centre.x);
        const int cj = cell(flake.centre.y);
        const int reach = std::min(1, m_cells / 2);  // a small grid: every cell once
        for (int di = -reach; di <= reach + (m_cells == 2 ? -1 : 0); ++di)
            for (int dj = -reach; dj <= reach + (m_cells == 2 ? -1 : 0); ++dj) {
                const std::size_t b = index(wrap(ci + di), wrap(cj + dj));
                for (std::size_t k : m_bins[b]) {
                    PlacedFlake other = placed[k];
                    other.centre.x -= m_side * std::round((other.centre.x - flake.centre.x) / m_side);
                    other.centre.y -= m_side * std::round((other.centre.y - flake.centre.y) / m_side);
                    if (disksIntersect(flake, other)) return true;
                }
            }
        return false;
    }

private:
    int cell(double x) const { return std::clamp(static_cast<int>(x / m_side * m_cells), 0, m_cells - 1); }
    int wrap(int i) const { return ((i % m_cells) + m_cells) % m_cells; }
    std::size_t index(int i, int j) const {
        return static_cast<std::size_t>(i) * static_cast<std::size_t>(m_cells) + static_cast<std::size_t>(j);
    }
    std::size_t bin(const Vec3& c) const { return index(cell(c.x), cell(c.y)); }

    static constexpr int kMaxCells = 256;  // wider cells only cost more candidate pairs
    double m_side;
    int m_cells;
    std::vector<std::vector<std::size_t>> m_bins;
};

// One flake (or one periodic copy of it) as Embree user geometry: the plane
// and the polygon in double (the ray is float). One cache line: the
// intersection callback is bound by loading it, so the in-plane basis is
// recomputed in the rare polygon-edge case instead of stored, and the
// rotation is kept as the float it was rounded to when the flake was placed.
struct alignas(64) FlakePrimitive {
    Vec3 centre;
    Vec3 normal;
    double radius_um = 0.0;   // circumradius of the polygon
    float rotation = 0.0F;    // of its first vertex from orthonormalBasis's b1 (the flake's plane) (radians)
    std::uint32_t flake = 0;  // index of the flake it copies (FlakeTile::flakes())
};
static_assert(sizeof(FlakePrimitive) == 64);

// For in-plane point (u, v) in the ring between the inscribed and the
// circumscribed circle of the regular `sides`-gon of circumradius r and
// apothem a whose first vertex is at angle `rotation`: whether it lies
// inside the edge of its sector.
bool insideRing(double u, double v, double apothem, double rotation, int sides) {
    const double kSector = 2.0 * std::numbers::pi / sides;
    double phi = std::atan2(v, u) - rotation;
    phi -= 2.0 * std::numbers::pi * std::floor(phi / (2.0 * std::numbers::pi));
    const double mid = rotation + (std::floor(phi / kSector) + 0.5) * kSector;
    return u * std::cos(mid) + v * std::sin(mid) <= apothem;
}

// Whether the point q (relative to the centre, in the plane of `normal`)
// lies in the flake's regular `sides`-gon of circumradius r (sides 0: the
// disk of radius r, |q| alone): inside the
// inscribed circle always, outside the circumscribed never (both need only
// |q|), and in the thin ring between (3.8 % of the disk for 16 sides)
// against the edge of its sector, in the in-plane basis of orthonormalBasis. This
// is exactly the polygon pointOnFlake samples and flakeAreaUm2 measures.
bool insidePolygon(const Vec3& q, const Vec3& normal, double r, double rotation, int sides) {
    const double rho2 = dot(q, q);
    if (rho2 > r * r) return false;
    if (sides == 0) return true;
    // cos(pi / n) once for the default shape: this runs on every candidate flake of a ray.
    static const double kDefaultApothemFactor = std::cos(std::numbers::pi / kFlakePolygonSides);
    const double apothem =
        r * (sides == kFlakePolygonSides ? kDefaultApothemFactor : std::cos(std::numbers::pi / sides));
    if (rho2 <= apothem * apothem) return true;
    Vec3 b1;
    Vec3 b2;
    orthonormalBasis(normal, b1, b2);
    return insideRing(dot(q, b1), dot(q, b2), apothem, rotation, sides);
}

// Interleaves the low 16 bits of x and y (x in the even bits): a Morton code.
std::uint32_t interleave16(std::uint32_t x, std::uint32_t y) {
    const auto spread = [](std::uint32_t v) {
        v &= 0xFFFFU;
        v = (v | (v << 8U)) & 0x00FF00FFU;
        v = (v | (v << 4U)) & 0x0F0F0F0FU;
        v = (v | (v << 2U)) & 0x33333333U;
        v = (v | (v << 1U)) & 0x55555555U;
        return v;
    };
    return spread(x) | (spread(y) << 1U);
}

// Orders the primitives along a Z-order curve of their lateral centres: a
// ray's candidates (the flakes above and below its track, drawn at random
// depths) then sit near each other in memory, which the intersection
// callback's loads feel (the placement order is by depth, i.e. laterally
// random). Only memory order changes: the nearest hit is the same.
void sortAlongZOrderCurve(std::vector<FlakePrimitive>& primitives, double side_um) {
    constexpr double kCells = 65535.0;
    const auto code = [side_um](const FlakePrimitive& p) {
        // Periodic copies lie up to a radius outside [0, L]: clamped to the edge cells.
        const auto cell = [side_um](double c) {
            return static_cast<std::uint32_t>(std::clamp(c / side_um, 0.0, 1.0) * kCells);
        };
        return interleave16(cell(p.centre.x), cell(p.centre.y));
    };
    std::vector<std::pair<std::uint32_t, std::size_t>> keys(primitives.size());
    for (std::size_t i = 0; i < primitives.size(); ++i) keys[i] = {code(primitives[i]), i};
    std::sort(keys.begin(), keys.end());
    std::vector<FlakePrimitive> sorted;
    sorted.reserve(primitives.size());
    for (const auto& key : keys) sorted.push_back(primitives[key.second]);
    primitives = std::move(sorted);
}

// One kind's primitives and the flakes' shape: Embree's user data of its geometry.
struct KindPrimitives {
    std::vector<FlakePrimitive> primitives;
    int sides = kFlakePolygonSides;  // 0: disks
};

void flakeBounds(const RTCBoundsFunctionArguments* args) {
    const auto& p = static_cast<const KindPrimitives*>(args->geometryUserPtr)->primitives.at(args->primID);
    // A disk's extent along axis i is r sqrt(1 - n_i^2), rounded outwards to
    // float and padded by a few float ulps of the coordinates, since Embree
    // walks the BVH with the ray rounded to float (DoubleRay).
    const double pad = 1e-6 * p.radius_um +
                       8.0 * static_cast<double>(std::numeric_limits<float>::epsilon()) *
                           (std::abs(p.centre.x) + std::abs(p.centre.y) + std::abs(p.centre.z) + p.radius_um);
    const auto half = [&p, pad](double n) {
        return p.radius_um * std::sqrt(std::max(0.0, 1.0 - n * n)) + pad;
    };
    const float inf = std::numeric_limits<float>::infinity();
    const auto down = [inf](double x) { return std::nextafter(static_cast<float>(x), -inf); };
    const auto up = [inf](double x) { return std::nextafter(static_cast<float>(x), inf); };
    args->bounds_o->lower_x = down(p.centre.x - half(p.normal.x));
    args->bounds_o->upper_x = up(p.centre.x + half(p.normal.x));
    args->bounds_o->lower_y = down(p.centre.y - half(p.normal.y));
    args->bounds_o->upper_y = up(p.centre.y + half(p.normal.y));
    args->bounds_o->lower_z = down(p.centre.z - half(p.normal.z));
    args->bounds_o->upper_z = up(p.centre.z + half(p.normal.z));
}

// The ray in double beside Embree's float copy (which only steers the BVH
// walk): the flakes are tested against it, so the distance, the t_near that
// keeps a ray off the flake it leaves, and the polygon test are exact to
// double rounding at any tile size. With the float ray, a ray leaving a flake
// at a grazing angle could meet that flake again (its float origin is up to
// ~6e-5 µm off the plane in a 1.8 mm tile), and a distance was off by as much.
// Embree hands the context to the callbacks; it must come first.
struct DoubleRay {
    RTCIntersectContext embree;
    Vec3 origin;
    Vec3 dir;
    double t_near = 0.0;
    double t_best = 0.0;  // t_far, then the nearest hit so far
    const FlakePrimitive* best = nullptr;
    unsigned geometry = RTC_INVALID_GEOMETRY_ID;
};

void flakeIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto& kind = *static_cast<const KindPrimitives*>(args->geometryUserPtr);
    const FlakePrimitive& p = kind.primitives[args->primID];
    auto* ray = reinterpret_cast<DoubleRay*>(args->context);  // NOLINT: Embree's documented context extension
    // FlakeTile::intersect traces single rays (rtcIntersect1: N = 1).
    if (args->N != 1 || args->valid[0] == 0) return;
    const double denom = dot(p.normal, ray->dir);
    if (denom == 0.0) return;  // in the plane of a thickness-less flake: no hit
    const Vec3 oc{p.centre.x - ray->origin.x, p.centre.y - ray->origin.y, p.centre.z - ray->origin.z};
    const double t = dot(p.normal, oc) / denom;
    if (!(t > ray->t_near) || !(t < ray->t_best)) return;
    const Vec3 q{ray->origin.x + t * ray->dir.x - p.centre.x, ray->origin.y + t * ray->dir.y - p.centre.y,
                 ray->origin.z + t * ray->dir.z - p.centre.z};
    if (!insidePolygon(q, p.normal, p.radius_um, static_cast<double>(p.rotation), kind.sides)) return;
    ray->t_best = t;
    ray->best = &p;
    ray->geometry = args->geomID;
    // Embree culls what lies beyond its float tfar: rounded up, so nothing nearer in double is lost.
    RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, 1), 1, 0) =
        std::nextafter(static_cast<float>(t), std::numeric_limits<float>::infinity());
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, 1);
    RTCHitN_Ng_x(hit, 1, 0) = static_cast<float>(p.normal.x);
    RTCHitN_Ng_y(hit, 1, 0) = static_cast<float>(p.normal.y);
    RTCHitN_Ng_z(hit, 1, 0) = static_cast<float>(p.normal.z);
    RTCHitN_u(hit, 1, 0) = 0.0F;
    RTCHitN_v(hit, 1, 0) = 0.0F;
    RTCHitN_primID(hit, 1, 0) = args->primID;
    RTCHitN_geomID(hit, 1, 0) = args->geomID;
    RTCHitN_instID(hit, 1, 0, 0) = args->context->instID[0];
}

}  // namespace

bool disksIntersect(const PlacedFlake& a, const PlacedFlake& b) {
    const Vec3 d = cross(a.normal, b.normal);
    const double dd = dot(d, d);
    const Vec3 ab{b.centre.x - a.centre.x, b.centre.y - a.centre.y, b.centre.z - a.centre.z};
    const double reach = a.radius_um + b.radius_um;
    if (dot(ab, ab) >= reach * reach) return false;
    if (dd < 1e-12) {
        // Parallel planes: only coplanar disks can meet (1e-9 µm: float-free exact data).
        return std::abs(dot(ab, a.normal)) < 1e-9;
    }
    // A point of the line where the planes n.x = h meet: (h_a (n_b x d) + h_b (d x n_a)) / |d|^2.
    const double ha = dot(a.normal, a.centre);
    const double hb = dot(b.normal, b.centre);
    const Vec3 p = cross(b.normal, d);
    const Vec3 q = cross(d, a.normal);
    const Vec3 p0{(ha * p.x + hb * q.x) / dd, (ha * p.y + hb * q.y) / dd, (ha * p.z + hb * q.z) / dd};
    const double len = std::sqrt(dd);
    const Vec3 u{d.x / len, d.y / len, d.z / len};
    // Each disk's chord on that line: [t - h, t + h] around the foot of its centre.
    auto chord = [&](const PlacedFlake& f, double& lo, double& hi) {
        const Vec3 c{f.centre.x - p0.x, f.centre.y - p0.y, f.centre.z - p0.z};
        const double t = dot(c, u);
        const double dist2 = dot(c, c) - t * t;
        const double r2 = f.radius_um * f.radius_um;
        if (dist2 >= r2) return false;
        const double h = std::sqrt(r2 - dist2);
        lo = t - h;
        hi = t + h;
        return true;
    };
    double a_lo = 0.0;
    double a_hi = 0.0;
    double b_lo = 0.0;
    double b_hi = 0.0;
    if (!chord(a, a_lo, a_hi) || !chord(b, b_lo, b_hi)) return false;
    return std::max(a_lo, b_lo) < std::min(a_hi, b_hi);
}

std::vector<FlakeGeometry> layerFlakeGeometries(const Layer& layer) {
    // Area density as layer_optics.cpp forms it (whole-layer mean), with the same "present" test.
    std::vector<FlakeGeometry> mirrors;
    std::vector<FlakeGeometry> pearls;
    for (const auto& component : layer.components) {
        if (const auto* m = std::get_if<MirrorFlake>(&component)) {
            const double density =
                m->volume_fraction * meanRelativeConcentration(m->depth_profile, 0.0, 1.0) / m->thickness_um;
            if (density > 0.0)
                mirrors.push_back({density, m->diameter_um, m->orientation_spread_deg,
                                   m->depth_profile ? &*m->depth_profile : nullptr, m->diameter_sd_um});
        } else if (const auto* p = std::get_if<InterferenceFlake>(&component)) {
            const double thickness_um = (p->mica_thickness_nm + 2.0 * p->tio2_thickness_nm) * 1e-3;
            const double density =
                thickness_um > 0.0 ? p->volume_fraction *
                                         meanRelativeConcentration(p->depth_profile, 0.0, 1.0) / thickness_um
                                   : 0.0;
            if (density > 0.0)
                pearls.push_back({density, p->diameter_um, p->orientation_spread_deg,
                                  p->depth_profile ? &*p->depth_profile : nullptr, p->diameter_sd_um});
        }
    }
    mirrors.insert(mirrors.end(), pearls.begin(), pearls.end());
    return mirrors;
}

struct FlakeTile::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<int> kind_of_geometry;
    std::vector<KindPrimitives> primitives;  // [geometry], stable once committed
    std::string error;
    ~Impl() {
        if (scene != nullptr) rtcReleaseScene(scene);
        if (device != nullptr) rtcReleaseDevice(device);
    }
    void check(const char* what) const {
        if (!error.empty()) throw Error(std::string("Embree (") + what + "): " + error);
    }
};

FlakeTile::FlakeTile(const std::vector<FlakeGeometry>& kinds, double top_um, double bottom_um,
                     std::uint64_t seed, int target_flakes, int max_flakes, bool reject_overlaps,
                     const std::atomic<bool>* stop, int polygon_sides)
    : m_impl(std::make_unique<Impl>()), m_sides(polygon_sides) {
    if (polygon_sides != 0 && polygon_sides < 3)
        throw InputError("settings", "flake_polygon_sides",
                         "must be 0 (disks) or at least 3, got " + std::to_string(polygon_sides));
    const auto stopped = [stop] { return stop != nullptr && stop->load(std::memory_order_relaxed); };
    const double height = bottom_um - top_um;
    double per_area = 0.0;  // flakes per µm^2 of surface
    double d_max = 0.0;
    for (const auto& k : kinds) {
        const DiameterLaw sizes(k);
        if (sizes.meanAreaUm2() > 0.0) per_area += k.area_density_per_um * height / sizes.meanAreaUm2();
        d_max = std::max(d_max, sizes.largestUm());
    }
    m_side_um = per_area > 0.0 ? std::max(2.0 * d_max, std::sqrt(target_flakes / per_area)) : 1.0;
    const double L = m_side_um;
    const double circumradius_factor = flakeCircumradiusFactor(m_sides);
    LateralGrid grid(L, std::max(0.5 * d_max * circumradius_factor, 1e-6));

    // No "threads=N" in the configuration: with it Embree's TBB tasking installs a
    // process-wide tbb::global_control(max_allowed_parallelism, N) for the
    // device's lifetime (embree common/tasking/taskschedulertbb.cpp), so
    // "threads=1" would run every explicit-flake job on one thread. The default
    // leaves TBB's parallelism to the caller (McSettings::threads).
    m_impl->device = rtcNewDevice(nullptr);
    if (m_impl->device == nullptr) throw Error("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(m_impl->device, onEmbreeError, &m_impl->error);
    m_impl->scene = rtcNewScene(m_impl->device);
    m_impl->check("scene");
    if (stop != nullptr) {
        // The BVH build is much of a tile's set-up (~23 ms for 20,000 flakes,
        // ~0.3 s for 200,000, more under load); Embree calls this from its
        // build threads and cancels the commit when it returns false.
        rtcSetSceneProgressMonitorFunction(
            m_impl->scene,
            [](void* flag, double) { return !static_cast<const std::atomic<bool>*>(flag)->load(); },
            const_cast<std::atomic<bool>*>(stop));  // Embree takes a void*; the monitor only reads
    }
    PathRng rng(seed, 0x666c616b65ULL, 0, 0);
    m_impl->primitives.reserve(kinds.size());  // Embree keeps a pointer to each kind's list
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        if (stopped()) throw Error("flake tile: cancelled");
        const FlakeGeometry& kind = kinds[k];
        const DiameterLaw sizes(kind);
        const double area = sizes.meanAreaUm2();
        if (!(area > 0.0) || !(kind.area_density_per_um > 0.0)) continue;
        const auto wanted = std::llround(kind.area_density_per_um * height * L * L / area);
        const auto count = std::min<long long>(wanted, max_flakes);
        if (count <= 0) continue;
        PathRng size_rng(seed, 0x73697a65ULL, k, 0);  // "size"
        const FlakeOrientation orientation(kind.spread_deg);
        KindPrimitives& kind_primitives = m_impl->primitives.emplace_back();
        kind_primitives.sides = m_sides;
        std::vector<FlakePrimitive>& primitives = kind_primitives.primitives;
        // Depths first, in order from the top: the normals are then assigned
        // from a Halton sequence (bases 2, 3) in that order, so that the flakes
        // of any depth range (a ray mostly meets the upper ones) represent D
        // evenly; independent draws would leave a tile-wide sampling error
        // that no path count reduces (measured: +-20 % in f at 2000 flakes).
        std::vector<double> depths(static_cast<std::size_t>(count));
        for (auto& z : depths) z = sampleDepth(kind.profile, rng);
        std::sort(depths.begin(), depths.end());
        const double shift1 = rng.uniform();
        const double shift2 = rng.uniform();
        for (long long f = 0; f < count; ++f) {
            const auto index = static_cast<std::uint64_t>(f);
            const FlakeNormal n = orientation.sample(std::fmod(radicalInverse(index, 2) + shift1, 1.0),
                                                     std::fmod(radicalInverse(index, 3) + shift2, 1.0));
            const Vec3 normal{n.x, n.y, n.z};
            const double radius = 0.5 * sizes.sample(size_rng) * circumradius_factor;
            // Keep the flake inside the film where it fits (a real flake cannot poke out).
            const double half_height = radius * std::sqrt(std::max(0.0, 1.0 - n.z * n.z));
            double z_rel = depths[static_cast<std::size_t>(f)];
            if (height > 2.0 * half_height) {
                const double lo = half_height / height;
                z_rel = lo + z_rel * (1.0 - 2.0 * lo);
            }
            Vec3 centre{rng.uniform() * L, rng.uniform() * L, -(top_um + z_rel * height)};
            if (reject_overlaps) {
                int tries = 0;
                while (grid.collides({centre, normal, radius, static_cast<int>(k)}, m_placed)) {
                    if (++tries == kPlacementTries)
                        throw InputError("recipe", "flakes",
                                         "no place without overlaps for flake " + std::to_string(f + 1) +
                                             " of " + std::to_string(count) + " (" +
                                             std::to_string(kind.diameter_um) +
                                             " µm): the concentration is too high to reject overlaps");
                    centre.x = rng.uniform() * L;
                    centre.y = rng.uniform() * L;
                }
            }
            // Rounded to float so that the primitive's copy of it is exact.
            const auto rotation_f = static_cast<float>(2.0 * std::numbers::pi * rng.uniform());
            const auto rotation = static_cast<double>(rotation_f);
            grid.add({centre, normal, radius, static_cast<int>(k), rotation}, m_placed.size());
            m_placed.push_back({centre, normal, radius, static_cast<int>(k), rotation});
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy) {
                    const double cx = centre.x + dx * L;
                    const double cy = centre.y + dy * L;
                    if (cx + radius < 0.0 || cx - radius > L || cy + radius < 0.0 || cy - radius > L)
                        continue;
                    primitives.push_back({{cx, cy, centre.z},
                                          normal,
                                          radius,
                                          rotation_f,
                                          static_cast<std::uint32_t>(m_placed.size() - 1)});
                }
            m_flakes += 1;
        }
        sortAlongZOrderCurve(primitives, L);
        // User geometry, one primitive per flake and periodic copy: 16 times
        // fewer primitives than the polygon's fan of triangles, so the BVH
        // build is that much shorter and a ray's traversal shallower.
        RTCGeometry geometry = rtcNewGeometry(m_impl->device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(primitives.size()));
        rtcSetGeometryUserData(geometry, &kind_primitives);
        rtcSetGeometryBoundsFunction(geometry, flakeBounds, nullptr);
        rtcSetGeometryIntersectFunction(geometry, flakeIntersect);
        m_impl->check("user geometry");
        rtcCommitGeometry(geometry);
        const unsigned id = rtcAttachGeometry(m_impl->scene, geometry);
        rtcReleaseGeometry(geometry);
        if (m_impl->kind_of_geometry.size() <= id) m_impl->kind_of_geometry.resize(id + 1, -1);
        m_impl->kind_of_geometry[id] = static_cast<int>(k);
    }
    rtcCommitScene(m_impl->scene);
    if (stopped()) throw Error("flake tile: cancelled");
    m_impl->check("commit");
}

FlakeTile::~FlakeTile() = default;
FlakeTile::FlakeTile(FlakeTile&&) noexcept = default;
FlakeTile& FlakeTile::operator=(FlakeTile&&) noexcept = default;

double FlakeTile::flakeAreaUm2(std::size_t i) const {
    const double r = m_placed[i].radius_um;
    if (m_sides == 0) return std::numbers::pi * r * r;
    return 0.5 * m_sides * r * r * std::sin(2.0 * std::numbers::pi / m_sides);
}

bool FlakeTile::onFlake(std::size_t i, const Vec3& relative) const {
    const PlacedFlake& f = m_placed[i];
    return insidePolygon(relative, f.normal, f.radius_um, f.rotation, m_sides);
}

Vec3 FlakeTile::pointOnFlake(std::size_t i, double u1, double u2, double u3) const {
    const PlacedFlake& f = m_placed[i];
    Vec3 b1;
    Vec3 b2;
    orthonormalBasis(f.normal, b1, b2);
    if (m_sides == 0) {
        // The disk: uniform over its area for the radius r sqrt(u2).
        const double rho = f.radius_um * std::sqrt(std::clamp(u2, 0.0, 1.0));
        const double phi = 2.0 * std::numbers::pi * u1;
        const double cu = rho * std::cos(phi);
        const double cv = rho * std::sin(phi);
        return {f.centre.x + cu * b1.x + cv * b2.x, f.centre.y + cu * b1.y + cv * b2.y,
                f.centre.z + cu * b1.z + cv * b2.z};
    }
    // The polygon as a fan of equal triangles (centre, vertex s, vertex s + 1).
    const double scaled = std::clamp(u1, 0.0, 1.0) * m_sides;
    const int s = std::min(static_cast<int>(scaled), m_sides - 1);
    const double phi0 = f.rotation + 2.0 * std::numbers::pi * s / m_sides;
    const double phi1 = f.rotation + 2.0 * std::numbers::pi * (s + 1) / m_sides;
    // Uniform in the triangle: sqrt(u2) along the median, u3 across (e.g. pbrt-v4, SampleUniformTriangle).
    const double a = std::sqrt(u2);
    const double w0 = a * (1.0 - u3) * f.radius_um;
    const double w1 = a * u3 * f.radius_um;
    const double cu = w0 * std::cos(phi0) + w1 * std::cos(phi1);
    const double cv = w0 * std::sin(phi0) + w1 * std::sin(phi1);
    return {f.centre.x + cu * b1.x + cv * b2.x, f.centre.y + cu * b1.y + cv * b2.y,
            f.centre.z + cu * b1.z + cv * b2.z};
}

FlakeHit FlakeTile::intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far) const {
    DoubleRay ray;
    rtcInitIntersectContext(&ray.embree);
    ray.origin = origin;
    ray.dir = dir;
    ray.t_near = t_near;
    ray.t_best = t_far;
    const float inf = std::numeric_limits<float>::infinity();
    RTCRayHit rh{};
    rh.ray.org_x = static_cast<float>(origin.x);
    rh.ray.org_y = static_cast<float>(origin.y);
    rh.ray.org_z = static_cast<float>(origin.z);
    rh.ray.dir_x = static_cast<float>(dir.x);
    rh.ray.dir_y = static_cast<float>(dir.y);
    rh.ray.dir_z = static_cast<float>(dir.z);
    // The float interval only culls the walk; widened so that it holds the double one.
    rh.ray.tnear = 0.0F;
    rh.ray.tfar = std::isfinite(t_far) ? std::nextafter(static_cast<float>(t_far), inf) : inf;
    rh.ray.mask = 0xFFFFFFFFU;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_impl->scene, &ray.embree, &rh);
    FlakeHit hit;
    if (ray.best == nullptr) return hit;
    hit.t = ray.t_best;
    hit.normal = ray.best->normal;
    hit.kind = m_impl->kind_of_geometry[ray.geometry];
    hit.flake = static_cast<std::int64_t>(ray.best->flake);
    return hit;
}

}  // namespace paintlab::mc
