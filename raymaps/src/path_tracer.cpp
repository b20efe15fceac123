#include "path_tracer.h"

#include "paintlab/engine/optics/fresnel.h"
#include "paintlab/raymaps/relight.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace paintlab::raymaps {

namespace {

// ---- non-delta BSDFs in the local frame (z = normal, both directions away) ----

// GGX (Trowbridge-Reitz) normal distribution and Smith's shadowing (Walter
// et al. 2007, eqs. 33 and 34).
double ggxD(double cos_h, double alpha) {
    const double a2 = alpha * alpha;
    const double d = (a2 - 1.0) * cos_h * cos_h + 1.0;
    return a2 / (kPi * d * d);
}
double smithG1(double mu, double alpha) {
    const double a2 = alpha * alpha;
    return 2.0 * mu / (mu + std::sqrt(a2 + (1.0 - a2) * mu * mu));
}

}  // namespace

// A non-delta surface: a scene material, or the paint through the relight
// tables' f_rgb (the reference renderer).
struct Surface {
    const Material& m;
    const RelightTables* paint = nullptr;
};

namespace {

// A glossy material: a Lambertian base under a rough dielectric coat; the
// base sees the light the coat transmits on the way in and out.
Rgb3 evalBsdf(const Surface& s, const Vec3& wo, const Vec3& wi) {
    const Material& m = s.m;
    const double mu_o = wo.z();
    const double mu_i = wi.z();
    if (!(mu_o > 0.0) || !(mu_i > 0.0)) return Rgb3::Zero();
    if (s.paint != nullptr) {
        const double to = std::hypot(wo.x(), wo.y());
        const double ti = std::hypot(wi.x(), wi.y());
        const double cos_dphi =
            to > 1e-9 && ti > 1e-9 ? (wo.x() * wi.x() + wo.y() * wi.y()) / (to * ti) : 1.0;
        return s.paint->lightTable(mu_o, mu_i, cos_dphi);
    }
    if (m.kind != MaterialKind::Glossy) return m.albedo / kPi;
    const Vec3 h = (wo + wi).normalized();
    const double alpha = std::max(m.roughness, 1e-3);
    const double f_h = fresnelDielectric(wi.dot(h), m.ior);
    const double spec =
        ggxD(h.z(), alpha) * smithG1(mu_o, alpha) * smithG1(mu_i, alpha) * f_h / (4.0 * mu_o * mu_i);
    const double transmit = (1.0 - fresnelDielectric(mu_o, m.ior)) * (1.0 - fresnelDielectric(mu_i, m.ior));
    return m.albedo * (transmit / kPi) + Rgb3::Constant(spec);
}

constexpr double kSpecularLobeProbability = 0.5;

double pdfBsdf(const Surface& s, const Vec3& wo, const Vec3& wi) {
    const Material& m = s.m;
    if (!(wo.z() > 0.0) || !(wi.z() > 0.0)) return 0.0;
    const double diffuse = wi.z() / kPi;
    if (s.paint != nullptr || m.kind != MaterialKind::Glossy) return diffuse;
    const Vec3 h = (wo + wi).normalized();
    const double alpha = std::max(m.roughness, 1e-3);
    const double spec = ggxD(h.z(), alpha) * h.z() / (4.0 * std::abs(wo.dot(h)));
    return kSpecularLobeProbability * spec + (1.0 - kSpecularLobeProbability) * diffuse;
}

// Returns false when no direction was produced.
bool sampleBsdf(const Surface& s, const Vec3& wo, Rng& rng, Vec3& wi) {
    const Material& m = s.m;
    const double u0 = rng.uniform();
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    if (s.paint == nullptr && m.kind == MaterialKind::Glossy && u0 < kSpecularLobeProbability) {
        // Half vector from D(h) cos(theta_h) (Walter et al. 2007, eqs. 35, 36).
        const double alpha = std::max(m.roughness, 1e-3);
        const double cos2 = (1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1);
        const double cos_h = std::sqrt(std::max(0.0, cos2));
        const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos2));
        const double phi = 2.0 * kPi * u2;
        const Vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
        wi = reflect(wo, h);
    } else {
        wi = sampleCosine(u1, u2);
    }
    return wi.z() > 0.0;
}

double powerHeuristic(double a, double b) { return a * a / (a * a + b * b); }

}  // namespace

PathTracer::PathTracer(const Scene& scene, const SceneTracer& tracer, const EnvironmentMap& environment,
                       int max_depth, const Rgb3& paint_proxy_albedo)
    : m_scene(scene), m_tracer(tracer), m_environment(environment), m_max_depth(max_depth) {
    for (const Light& light : scene.lights) {
        if (const auto* sun = std::get_if<SunLight>(&light)) {
            m_suns.push_back({sun->direction.normalized(), sun->irradiance,
                              std::cos(0.5 * sun->angular_diameter_deg * kPi / 180.0)});
        } else if (const auto* point = std::get_if<PointLight>(&light)) {
            m_points.push_back({point->position, point->intensity});
        }
    }
    m_paint_proxy.kind = MaterialKind::Diffuse;
    m_paint_proxy.albedo = paint_proxy_albedo;
}

Vec3 PathTracer::offset(const Vec3& position, const Vec3& geometric_normal, const Vec3& towards) const {
    const double side = geometric_normal.dot(towards) >= 0.0 ? 1.0 : -1.0;
    return position + side * m_tracer.epsilon() * geometric_normal;
}

Rgb3 PathTracer::escaped(const Vec3& direction, bool see_sun_disks) const {
    Rgb3 l = m_environment.radiance(direction);
    if (see_sun_disks)
        for (const auto& sun : m_suns) {
            if (direction.dot(sun.direction) < sun.cos_half_angle) continue;
            // A uniform disk: radiance = irradiance / solid angle.
            const double solid_angle = 2.0 * kPi * (1.0 - sun.cos_half_angle);
            if (solid_angle > 0.0) l += sun.irradiance / solid_angle;
        }
    return l;
}

double PathTracer::sunVisibility(const Vec3& point, const Vec3& normal, const DirectionalLight& sun, int rays,
                                 Rng& rng) const {
    const Frame frame = Frame::fromNormal(sun.direction);
    const Vec3 origin = offset(point, normal, sun.direction);
    int visible = 0;
    for (int i = 0; i < rays; ++i) {
        // Stratified in the cone's polar coordinate.
        const Vec3 d =
            frame.toWorld(sampleCone((i + rng.uniform()) / rays, rng.uniform(), sun.cos_half_angle));
        if (!m_tracer.occluded(origin, d)) ++visible;
    }
    return static_cast<double>(visible) / rays;
}

bool PathTracer::pointVisible(const Vec3& point, const Vec3& normal, const PositionalLight& light) const {
    const Vec3 to = light.position - point;
    const Vec3 origin = offset(point, normal, to);
    return !m_tracer.occluded(origin, to, 1.0 - 1e-4);
}

Rgb3 PathTracer::directLight(const Hit& hit, const Vec3& wo, const Frame& frame, const Surface& m,
                             Rng& rng) const {
    Rgb3 l = Rgb3::Zero();
    const Vec3 wo_local = frame.toLocal(wo);
    for (const auto& sun : m_suns) {
        const Vec3 d = Frame::fromNormal(sun.direction)
                           .toWorld(sampleCone(rng.uniform(), rng.uniform(), sun.cos_half_angle));
        const Vec3 wi = frame.toLocal(d);
        if (!(wi.z() > 0.0)) continue;
        if (m_tracer.occluded(offset(hit.position, hit.geometric_normal, d), d)) continue;
        l += evalBsdf(m, wo_local, wi).cwiseProduct(sun.irradiance) * wi.z();
    }
    for (const auto& point : m_points) {
        const Vec3 to = point.position - hit.position;
        const double r2 = to.squaredNorm();
        const Vec3 wi = frame.toLocal(to / std::sqrt(r2));
        if (!(wi.z() > 0.0) || !pointVisible(hit.position, hit.geometric_normal, point)) continue;
        l += evalBsdf(m, wo_local, wi).cwiseProduct(point.intensity) * (wi.z() / r2);
    }
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const EnvironmentMap::Sample s = m_environment.sampleFacing(frame.z, u1, u2);
    const Vec3 wi = frame.toLocal(s.direction);
    if (wi.z() > 0.0 && s.pdf_sr > 0.0 &&
        !m_tracer.occluded(offset(hit.position, hit.geometric_normal, s.direction), s.direction)) {
        const double weight = powerHeuristic(s.pdf_sr, pdfBsdf(m, wo_local, wi));
        l += evalBsdf(m, wo_local, wi).cwiseProduct(s.radiance) * (wi.z() * weight / s.pdf_sr);
    }
    return l;
}

Vec3 PathTracer::deltaBounce(const Material& m, const Hit& hit, const Vec3& direction, Rng& rng,
                             Rgb3& beta) const {
    if (m.kind == MaterialKind::Mirror) {
        const Vec3 wo = -direction;
        const Vec3 ng =
            hit.geometric_normal.dot(wo) >= 0.0 ? hit.geometric_normal : Vec3(-hit.geometric_normal);
        Vec3 ns = hit.shading_normal.dot(ng) >= 0.0 ? hit.shading_normal : Vec3(-hit.shading_normal);
        if (ns.dot(wo) <= 0.0) ns = ng;
        beta = beta.cwiseProduct(m.albedo);
        const Vec3 dir = reflect(wo, ns);
        return dir.dot(ng) > 0.0 ? dir : reflect(wo, ng);
    }
    // A smooth dielectric: reflect or refract with the Fresnel probability,
    // so the throughput is unchanged (clear glass).
    const GlassSplit split = glassSplit(m, hit, direction);
    return rng.uniform() < split.reflectance ? split.reflected : split.refracted;
}

PathTracer::GlassSplit PathTracer::glassSplit(const Material& m, const Hit& hit,
                                              const Vec3& direction) const {
    const Vec3 wo = -direction;
    const Vec3 ng = hit.geometric_normal.dot(wo) >= 0.0 ? hit.geometric_normal : Vec3(-hit.geometric_normal);
    Vec3 ns = hit.shading_normal.dot(ng) >= 0.0 ? hit.shading_normal : Vec3(-hit.shading_normal);
    if (ns.dot(wo) <= 0.0) ns = ng;
    const bool entering = hit.geometric_normal.dot(wo) >= 0.0;
    const double eta = entering ? m.ior : 1.0 / m.ior;
    const double cos_i = std::clamp(wo.dot(ns), 0.0, 1.0);
    GlassSplit split;
    split.reflectance = std::clamp(fresnelDielectric(cos_i, eta), 0.0, 1.0);
    split.reflected = reflect(wo, ns);
    split.refracted = split.reflected;  // total internal reflection
    if (split.reflectance < 1.0) {
        const double cos_t = refractedCos(cos_i, eta);
        split.refracted = (-wo / eta + (cos_i / eta - cos_t) * ns).normalized();
    }
    return split;
}

std::uint64_t PathTracer::raysTraced() const { return m_tracer.raysTraced(); }

Rgb3 PathTracer::radiance(const Vec3& origin, const Vec3& direction, Rng& rng, bool see_sun_disks,
                          const EnvironmentMap* first_escape) const {
    return radianceAt(m_tracer.intersect(origin, direction), direction, rng, see_sun_disks, first_escape);
}

Rgb3 PathTracer::radianceAt(const Hit& first, const Vec3& direction, Rng& rng, bool see_sun_disks,
                            const EnvironmentMap* first_escape) const {
    Rgb3 l = Rgb3::Zero();
    Rgb3 beta = Rgb3::Ones();
    Hit hit = first;
    Vec3 dir = direction;
    double previous_pdf = 0.0;             // of the BSDF sample that made this ray; 0 after a delta (no MIS)
    Vec3 previous_normal = Vec3::UnitY();  // of that vertex: its next-event distribution (sampleFacing)
    bool sun_disks = see_sun_disks;
    // `depth` counts the surface vertices that scatter (diffuse, glossy,
    // paint): a mirror or glass bounce adds no vertex, so a moment ray
    // (indirect_depth 2) that meets a mirror still sees what the mirror shows
    // lit by next-event estimation plus a bounce (counting them lost ~4 % of
    // the light of a sphere beside a mirror against the reference). Delta
    // bounces are capped apart.
    constexpr int kMaxDeltaBounces = 16;
    int delta_bounces = 0;
    for (int depth = 0, segment = 0;; ++segment) {
        if (!hit.found) {
            if (segment == 0 && first_escape != nullptr)
                return escaped(dir, sun_disks) - m_environment.radiance(dir) + first_escape->radiance(dir);
            const Rgb3 env = m_environment.radiance(dir);
            const double weight =
                previous_pdf > 0.0
                    ? powerHeuristic(previous_pdf, m_environment.pdfFacing(previous_normal, dir))
                    : 1.0;
            l += beta.cwiseProduct(env * weight + (escaped(dir, sun_disks) - env));
            break;
        }
        const Material& m = m_scene.materials[static_cast<std::size_t>(hit.material)];
        const Vec3 wo = -dir;
        const Vec3 ng =
            hit.geometric_normal.dot(wo) >= 0.0 ? hit.geometric_normal : Vec3(-hit.geometric_normal);
        Vec3 ns = hit.shading_normal.dot(ng) >= 0.0 ? hit.shading_normal : Vec3(-hit.shading_normal);
        if (ns.dot(wo) <= 0.0) ns = ng;
        if (m.kind == MaterialKind::Emissive) {
            l += beta.cwiseProduct(m.radiance);
            break;
        }
        if (m.kind == MaterialKind::Mirror || m.kind == MaterialKind::Glass) {
            if (++delta_bounces > kMaxDeltaBounces) break;
            dir = deltaBounce(m, hit, dir, rng, beta);
            previous_pdf = 0.0;
        } else {
            if (depth >= m_max_depth) break;
            ++depth;
            const bool paint = m.kind == MaterialKind::Paint;
            if (paint && m_paint != nullptr) {
                // The clear coat's mirror term, chosen with probability
                // p = its largest channel (throughput R / p), else the rest
                // of the BRDF (throughput 1 / (1 - p)).
                const Rgb3 r = m_paint->coat(wo.dot(ns));
                const double p = std::clamp(r.maxCoeff(), 0.0, 0.95);
                if (rng.uniform() < p) {
                    beta = beta.cwiseProduct(r) / p;
                    dir = reflect(wo, ns);
                    if (dir.dot(ng) <= 0.0) dir = reflect(wo, ng);
                    previous_pdf = 0.0;
                    hit = m_tracer.intersect(offset(hit.position, hit.geometric_normal, dir), dir);
                    continue;
                }
                beta /= 1.0 - p;
            }
            const Surface surface{paint && m_paint == nullptr ? m_paint_proxy : m, paint ? m_paint : nullptr};
            const Frame frame = Frame::fromNormal(ns);
            l += beta.cwiseProduct(directLight(hit, wo, frame, surface, rng));
            Vec3 wi_local;
            const Vec3 wo_local = frame.toLocal(wo);
            if (!sampleBsdf(surface, wo_local, rng, wi_local)) break;
            const double pdf = pdfBsdf(surface, wo_local, wi_local);
            if (!(pdf > 0.0)) break;
            dir = frame.toWorld(wi_local);
            if (dir.dot(ng) <= 0.0) break;
            beta = beta.cwiseProduct(evalBsdf(surface, wo_local, wi_local)) * (wi_local.z() / pdf);
            previous_pdf = pdf;
            previous_normal = ns;
            sun_disks = false;  // the suns were sampled by next-event estimation
        }
        hit = m_tracer.intersect(offset(hit.position, hit.geometric_normal, dir), dir);
    }
    return l;
}

}  // namespace paintlab::raymaps
