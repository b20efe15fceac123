#pragma once
// A small path tracer for what is not the paint (docs/RAYMAPS.md): the baked
// radiance of non-paint pixels and the radiance that the paint's light
// moments and mirror term see. Next-event estimation towards the suns, the
// point lights and the environment (importance sampled, EnvironmentMap::sample),
// combined with BSDF sampling by multiple importance sampling (power
// heuristic, Veach 1997, ch. 9) for diffuse and glossy surfaces; mirrors and
// glass are followed as deltas.
//
// Paint met by a secondary ray (paint seen by paint, or lighting the floor)
// is a Lambertian proxy: grey of albedo kPaintProxyAlbedo when the recipe is
// not known at precompute, else the recipe's diffuse albedo in linear sRGB
// (RayMapSettings::paint_proxy_albedo). The light that paint sends onto other
// surfaces is a second-order term, but paint seen in a mirror lights the paint
// itself, and a grey stand-in for a red paint there biased green and blue by
// ~3 % (docs/RAYMAPS.md, "Per-pixel comparison").

#include "sampling.h"
#include "scene_tracer.h"

#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/scene.h"

#include <vector>

namespace paintlab::raymaps {

class RelightTables;
struct Surface;

constexpr double kPaintProxyAlbedo = 0.35;

struct DirectionalLight {
    Vec3 direction;  // towards the light, unit
    Rgb3 irradiance;
    double cos_half_angle = 1.0;  // of the sun's disk
};
struct PositionalLight {
    Vec3 position;
    Rgb3 intensity;
};

class PathTracer {
public:
    PathTracer(const Scene& scene, const SceneTracer& tracer, const EnvironmentMap& environment,
               int max_depth, const Rgb3& paint_proxy_albedo = Rgb3::Constant(kPaintProxyAlbedo));

    // Radiance arriving at `origin` from `direction` (unit): what the ray
    // towards `direction` sees. `see_sun_disks`: whether a ray that escapes
    // inside a sun's disk gets its radiance (yes for camera and mirror rays;
    // no where the suns are explicit lights already).
    // `first_escape`: if given, the environment a ray that escapes at once
    // sees (the residual after hotspot extraction, for the paint's moment rays).
    Rgb3 radiance(const Vec3& origin, const Vec3& direction, Rng& rng, bool see_sun_disks,
                  const EnvironmentMap* first_escape = nullptr) const;
    // The same from a hit already found along `direction`.
    Rgb3 radianceAt(const Hit& hit, const Vec3& direction, Rng& rng, bool see_sun_disks,
                    const EnvironmentMap* first_escape = nullptr) const;

    // Environment plus (optionally) the suns' disks, for a ray that escapes.
    Rgb3 escaped(const Vec3& direction, bool see_sun_disks) const;
    // Fraction of `rays` shadow rays from `point` that reach the sun's disk.
    double sunVisibility(const Vec3& point, const Vec3& normal, const DirectionalLight& sun, int rays,
                         Rng& rng) const;
    bool pointVisible(const Vec3& point, const Vec3& normal, const PositionalLight& light) const;

    const std::vector<DirectionalLight>& suns() const { return m_suns; }
    const std::vector<PositionalLight>& points() const { return m_points; }
    const SceneTracer& tracer() const { return m_tracer; }
    // Lifts a ray origin off the surface on the side of `towards`.
    Vec3 offset(const Vec3& position, const Vec3& geometric_normal, const Vec3& towards) const;
    // The continuation of a ray that met a mirror or glass surface (kind
    // Mirror or Glass) along `direction`; beta takes the mirror's colour.
    Vec3 deltaBounce(const Material& m, const Hit& hit, const Vec3& direction, Rng& rng, Rgb3& beta) const;
    // Both continuations of a ray that met glass along `direction`: the
    // mirror and the refracted direction, and the Fresnel reflectance F
    // (1 under total internal reflection, refracted = reflected then).
    struct GlassSplit {
        Vec3 reflected;
        Vec3 refracted;
        double reflectance = 0.0;
    };
    GlassSplit glassSplit(const Material& m, const Hit& hit, const Vec3& direction) const;
    const Material& material(const Hit& hit) const {
        return m_scene.materials[static_cast<std::size_t>(hit.material)];
    }
    std::uint64_t raysTraced() const;
    // Shade the paint with these tables' f_rgb and clear-coat mirror term
    // (the brute-force reference) instead of the grey proxy.
    void setPaint(const RelightTables* tables) { m_paint = tables; }

private:
    Rgb3 directLight(const Hit& hit, const Vec3& wo, const Frame& frame, const Surface& m, Rng& rng) const;

    const Scene& m_scene;
    const SceneTracer& m_tracer;
    const EnvironmentMap& m_environment;
    int m_max_depth;
    std::vector<DirectionalLight> m_suns;
    std::vector<PositionalLight> m_points;
    Material m_paint_proxy;
    const RelightTables* m_paint = nullptr;
};

}  // namespace paintlab::raymaps
