#pragma once
// What the ray-map precompute traces for one pixel (docs/RAYMAPS.md, "As
// built"): its camera samples through mirrors and glass, the baked radiance
// where they meet other surfaces, and where they meet the paint the sums of
// its record (frame at the pixel centre, weight, light moments, explicit
// lights' visibility, mirror radiance). Private to raymap_build.cpp.

#include "environment_moments.h"
#include "path_tracer.h"
#include "sampling.h"
#include "scene_tracer.h"

#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/raymap.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace paintlab::raymaps {

// What the camera samples of one pixel found on the paint, summed.
struct PaintAccumulator {
    int samples = 0;
    Vec3 normal, view, position;
    double footprint = 0.0;
    double frame_offset2 = 0.0;  // squared distance of the frame's sample from the pixel centre
    bool centred = false;        // the frame is the pixel centre's
    // The pixel's random stratification of the moment rays (addMoments).
    std::vector<double> cell_rotation;
    std::vector<std::uint32_t> mu_scramble;
    std::uint32_t env_scramble = 0;
    Rgb3 weight = Rgb3::Zero();
    Rgb3 mirror = Rgb3::Zero();
    bool mirror_fixed = false;  // mirror is the pixel's fixed grid's (mirrorTerm), else the samples' sum
    std::vector<Rgb3> moments;  // [j * orders + m]
    std::vector<double> visibility;
};

class PixelTracer {
public:
    // `pt` bakes the non-paint samples; `indirect` (shorter paths) serves the
    // paint's moment and mirror rays.
    // `hotspots`: the environment's extracted lights; `residual`: the
    // environment without them, seen by the moment rays that escape.
    PixelTracer(const PathTracer& pt, const PathTracer& indirect, const PinholeCamera& camera,
                const RayMapSettings& s, int width, const std::vector<DirectionalLight>& hotspots,
                const EnvironmentMap& residual, const EnvironmentMoments* environment_moments)
        : m_pt(pt), m_indirect(indirect), m_camera(camera), m_s(s), m_width(width),
          m_lights(static_cast<int>(pt.suns().size() + pt.points().size() + hotspots.size())),
          m_hotspots(hotspots), m_residual(residual), m_environment_moments(environment_moments) {
        m_side = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(s.aa_samples)))));
        const int samples = m_side * m_side;
        // Equally spaced azimuths (one random rotation per cell): the moments
        // of a light that varies slowly in azimuth are exact for orders below
        // this count, so it is at least M_L.
        m_azimuths = std::max(s.orders, (s.light_rays + s.cells * samples - 1) / (s.cells * samples));
        m_env_rays = (s.environment_rays + samples - 1) / samples;
        // The mirror grid: twice the camera samples' side; where a mirror ray
        // meets a surface, bake_paths / 2 paths (16 points x 2 paths at the
        // defaults: twice the paths of one mirror ray per camera sample).
        m_mirror_side = 2 * m_side;
        m_mirror_paths = std::max(1, s.bake_paths / 2);
    }

    // Returns the baked radiance; fills `paint` if a sample met the paint.
    Rgb3 trace(int x, int y, PaintAccumulator& paint) const {
        const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(m_width) +
                           static_cast<std::uint64_t>(x);
        Rng rng(m_s.seed, pixel, 0);
        const int samples = m_side * m_side;
        Rgb3 baked = Rgb3::Zero();
        paint.samples = 0;
        paint.weight.setZero();
        paint.mirror.setZero();
        paint.moments.assign(static_cast<std::size_t>(m_s.cells) * static_cast<std::size_t>(m_s.orders),
                             Rgb3::Zero());
        paint.visibility.assign(static_cast<std::size_t>(m_lights), 0.0);
        centreFrame(x, y, paint);
        paint.cell_rotation.resize(static_cast<std::size_t>(m_s.cells));
        paint.mu_scramble.resize(static_cast<std::size_t>(m_s.cells));
        for (std::size_t j = 0; j < paint.cell_rotation.size(); ++j) {
            paint.cell_rotation[j] = rng.uniform();
            paint.mu_scramble[j] = rng.next();
        }
        paint.env_scramble = rng.next();
        paint.mirror_fixed = mirrorTerm(x, y, rng, paint.mirror);
        for (int sy = 0; sy < m_side; ++sy)
            for (int sx = 0; sx < m_side; ++sx) {
                const double px = x + (sx + rng.uniform()) / m_side;
                const double py = y + (sy + rng.uniform()) / m_side;
                const double offset2 = (px - x - 0.5) * (px - x - 0.5) + (py - y - 0.5) * (py - y - 0.5);
                baked += traceSample(m_camera.direction(px, py), offset2, sy * m_side + sx, rng, paint);
            }
        if (paint.samples > 0) {
            const double inv = 1.0 / paint.samples;
            for (Rgb3& l : paint.moments) l *= inv;
            // The rays estimated L - E; E's moments are computed (environment_moments.h).
            if (m_environment_moments != nullptr)
                m_environment_moments->add(Frame::fromNormalAndTangent(paint.normal, paint.view), m_s.cells,
                                           m_s.orders, paint.moments);
            for (double& v : paint.visibility) v *= inv;
            if (!paint.mirror_fixed) paint.mirror *= inv;
            paint.weight /= samples;
        }
        return baked / samples;
    }

private:
    // offset2: the sample's squared distance from the pixel centre (pixels).
    Rgb3 traceSample(Vec3 dir, double offset2, int sample, Rng& rng, PaintAccumulator& paint) const {
        Vec3 origin = m_camera.origin();
        Rgb3 beta = Rgb3::Ones();
        Rgb3 baked = Rgb3::Zero();  // what the glass's other branches see
        double distance = 0.0;
        for (int bounce = 0;; ++bounce) {
            const Hit hit = m_pt.tracer().intersect(origin, dir);
            if (!hit.found) return baked + beta.cwiseProduct(m_pt.escaped(dir, true));
            distance += hit.t;
            const Material& m = m_pt.material(hit);
            if (m.kind == MaterialKind::Paint) {
                addPaint(hit, dir, beta, distance, offset2, sample, rng, paint);
                return baked;
            }
            if (m.kind == MaterialKind::Mirror && bounce < m_s.max_delta_bounces) {
                dir = m_pt.deltaBounce(m, hit, dir, rng, beta);
                origin = m_pt.offset(hit.position, hit.geometric_normal, dir);
                continue;
            }
            if (m.kind == MaterialKind::Glass && bounce < m_s.max_delta_bounces) {
                // Both Fresnel branches, not a random choice between them (a
                // pixel behind a pane would be all paint or all reflection):
                // the camera path follows the stronger one with throughput
                // F or 1 - F, the other is path traced into the baked
                // radiance (paint it meets is the grey proxy there, a
                // second-order error: F ~ 4 % for a pane seen head-on).
                const PathTracer::GlassSplit split = m_pt.glassSplit(m, hit, dir);
                const bool reflect = split.reflectance >= 0.5;
                const double follow = reflect ? split.reflectance : 1.0 - split.reflectance;
                const Vec3 side = reflect ? split.refracted : split.reflected;
                if (follow < 1.0) {
                    const Vec3 side_origin = m_pt.offset(hit.position, hit.geometric_normal, side);
                    baked +=
                        (beta * (1.0 - follow)).cwiseProduct(m_pt.radiance(side_origin, side, rng, true));
                }
                beta *= follow;
                dir = reflect ? split.reflected : split.refracted;
                origin = m_pt.offset(hit.position, hit.geometric_normal, dir);
                continue;
            }
            Rgb3 l = Rgb3::Zero();
            for (int k = 0; k < m_s.bake_paths; ++k) l += m_pt.radianceAt(hit, dir, rng, true);
            return baked + beta.cwiseProduct(l) / m_s.bake_paths;
        }
    }

    // Geometric and shading normal on the side of wo.
    static std::pair<Vec3, Vec3> paintNormals(const Hit& hit, const Vec3& wo) {
        const Vec3 ng =
            hit.geometric_normal.dot(wo) >= 0.0 ? hit.geometric_normal : Vec3(-hit.geometric_normal);
        Vec3 ns = hit.shading_normal.dot(ng) >= 0.0 ? hit.shading_normal : Vec3(-hit.shading_normal);
        if (ns.dot(wo) <= 1e-3) ns = ng;  // silhouettes: the interpolated normal faces away
        return {ng, ns};
    }

    void setFrame(const Hit& hit, const Vec3& dir, double distance, double offset2,
                  PaintAccumulator& paint) const {
        paint.frame_offset2 = offset2;
        paint.normal = paintNormals(hit, -dir).second;
        paint.view = -dir;
        paint.position = hit.position;
        paint.footprint = distance * m_camera.pixelAngle();
    }

    // Where the camera ray through image point (px, py) meets the paint,
    // through mirrors and the stronger branch of glass as the camera samples
    // go; no random number is drawn (a mirror draws none), so the answer is
    // the same for every seed. found is false if it meets anything else.
    struct PaintHit {
        Hit hit;
        Vec3 dir;
        double distance = 0.0;
    };
    PaintHit paintAt(double px, double py) const {
        PaintHit out;
        Vec3 dir = m_camera.direction(px, py);
        Vec3 origin = m_camera.origin();
        Rng unused(0, 0, 0);
        for (int bounce = 0;; ++bounce) {
            const Hit hit = m_pt.tracer().intersect(origin, dir);
            if (!hit.found) return out;
            out.distance += hit.t;
            const Material& m = m_pt.material(hit);
            if (m.kind == MaterialKind::Paint) {
                out.hit = hit;
                out.dir = dir;
                return out;
            }
            if (bounce >= m_s.max_delta_bounces) return out;
            if (m.kind == MaterialKind::Mirror) {
                Rgb3 beta = Rgb3::Ones();
                dir = m_pt.deltaBounce(m, hit, dir, unused, beta);
            } else if (m.kind == MaterialKind::Glass) {
                const PathTracer::GlassSplit split = m_pt.glassSplit(m, hit, dir);
                dir = split.reflectance >= 0.5 ? split.reflected : split.refracted;
            } else {
                return out;
            }
            origin = m_pt.offset(hit.position, hit.geometric_normal, dir);
        }
    }

    // The record's one frame (normal, view, position, footprint) is the
    // paint's at the pixel centre (paintAt): the same for every seed. The
    // sample nearest the centre, used before, moved with the jitter, and the
    // explicit lights, the coat and the moments with it (~2 % per-pixel noise
    // on the sun-lit demo scene whatever the number of rays).
    void centreFrame(int x, int y, PaintAccumulator& paint) const {
        const PaintHit p = paintAt(x + 0.5, y + 0.5);
        paint.centred = p.hit.found;
        if (p.hit.found) setFrame(p.hit, p.dir, p.distance, -1.0, paint);
    }

    // What the clear coat mirrors, averaged over a fixed grid of
    // m_mirror_side^2 points of the pixel (the same points for every seed):
    // where the mirror ray escapes, the environment in that direction, a
    // deterministic lookup; where it meets a surface, the path-traced
    // radiance there (the one random part). One jittered ray per camera
    // sample, used before, aliased the reflections' sharp edges differently
    // for every seed: 2-22 % per-pixel noise of this term under the
    // courtyard HDR (docs/PERFORMANCE.md). Returns false if no point of
    // the grid meets the paint (a pixel at the paint's edge).
    bool mirrorTerm(int x, int y, Rng& rng, Rgb3& mirror) const {
        mirror.setZero();
        int found = 0;
        for (int sy = 0; sy < m_mirror_side; ++sy)
            for (int sx = 0; sx < m_mirror_side; ++sx) {
                const PaintHit p = paintAt(x + (sx + 0.5) / m_mirror_side, y + (sy + 0.5) / m_mirror_side);
                if (!p.hit.found) continue;
                ++found;
                mirror += mirrorRadiance(p.hit, -p.dir, m_mirror_paths, rng);
            }
        if (found > 0) mirror /= found;
        return found > 0;
    }

    // The coat's mirror radiance at a paint hit seen from wo: one ray, and
    // `paths` paths from what it meets (the floor's path-traced radiance).
    Rgb3 mirrorRadiance(const Hit& hit, const Vec3& wo, int paths, Rng& rng) const {
        const auto [ng, ns] = paintNormals(hit, wo);
        const Vec3 origin = m_pt.offset(hit.position, ng, ng);
        Vec3 r = reflect(wo, ns);
        if (r.dot(ng) <= 0.0) r = reflect(wo, ng);
        const Hit mirrored = m_indirect.tracer().intersect(origin, r);
        if (!mirrored.found) return m_indirect.escaped(r, true);
        Rgb3 l = Rgb3::Zero();
        for (int p = 0; p < paths; ++p) l += m_indirect.radianceAt(mirrored, r, rng, true);
        return l / paths;
    }

    void addPaint(const Hit& hit, const Vec3& dir, const Rgb3& beta, double distance, double offset2,
                  int sample, Rng& rng, PaintAccumulator& paint) const {
        const Vec3 wo = -dir;
        const auto [ng, ns] = paintNormals(hit, wo);
        // x towards the view: the azimuth of wi is measured from the view's.
        const Frame frame = Frame::fromNormalAndTangent(ns, wo);
        const Vec3 origin = m_pt.offset(hit.position, ng, ng);
        // Without a paint hit at the pixel centre (centreFrame), the frame
        // of the paint sample nearest to it.
        if (!paint.centred && (paint.samples == 0 || offset2 < paint.frame_offset2))
            setFrame(hit, dir, distance, offset2, paint);
        ++paint.samples;
        paint.weight += beta;

        addMoments(frame, origin, ng, sample, rng, paint);
        std::size_t k = 0;
        for (const auto& sun : m_pt.suns())
            paint.visibility[k++] += m_pt.sunVisibility(hit.position, ng, sun, m_s.sun_shadow_rays, rng);
        for (const auto& point : m_pt.points())
            paint.visibility[k++] += m_pt.pointVisible(hit.position, ng, point) ? 1.0 : 0.0;
        for (const auto& spot : m_hotspots)
            paint.visibility[k++] += m_pt.sunVisibility(hit.position, ng, spot, m_s.sun_shadow_rays, rng);
        // The coat's mirror term of an edge pixel (mirrorTerm found no paint).
        if (!paint.mirror_fixed) paint.mirror += mirrorRadiance(hit, wo, m_s.bake_paths, rng);
    }

    // Light moments l^m_j = integral over cell j of L cos(m phi) mu dw
    // (cell j: mu^2 in [j/J, (j+1)/J]), from two kinds of rays combined by
    // the balance heuristic (Veach 1997, ch. 9): per cell, m_azimuths rays
    // uniform in projected solid angle (density mu J / pi; azimuths equally
    // spaced with one random rotation, mu^2 jittered), and m_env_rays
    // rays importance sampled on the residual environment (its pdf), which
    // find the bright part of an HDR that uniform rays hit or miss at random.
    // With the control variate (environment_moments.h) the rays carry L - E.
    void addMoments(const Frame& frame, const Vec3& origin, const Vec3& ng, int sample, Rng& rng,
                    PaintAccumulator& paint) const {
        const int cells = m_s.cells;
        const auto orders = static_cast<std::size_t>(m_s.orders);
        const double uniform_density = m_azimuths * cells / kPi;  // x mu: all uniform rays of a cell
        // One direction (local to the frame) in cell j, with the env rays' combined density.
        const auto add = [&](const Vec3& local, int j, double env_density) {
            const double mu = local.z();
            const Vec3 w = frame.toWorld(local);
            // Below the triangle's own plane (shading normal != geometric
            // normal): mirrored above it, where the light is most alike.
            const Vec3 wi = w.dot(ng) <= 0.0 ? Vec3(w - 2.0 * w.dot(ng) * ng) : w;
            Rgb3 l = m_indirect.radiance(origin, wi, rng, false, &m_residual);
            // With the control variate, what the scene changes: L - E
            // (zero for a ray that escapes unmirrored).
            if (m_environment_moments != nullptr) l -= m_residual.radiance(w);
            l *= mu / (uniform_density * mu + m_env_rays * env_density);
            const double sin_theta = std::hypot(local.x(), local.y());
            const double c1 = sin_theta > 1e-12 ? local.x() / sin_theta : 1.0;
            double previous = 1.0;
            double current = c1;
            const std::size_t at = static_cast<std::size_t>(j) * orders;
            paint.moments[at] += l;
            for (std::size_t m = 1; m < orders; ++m) {  // cos(m phi): Chebyshev recurrence
                paint.moments[at + m] += l * current;
                const double next = 2.0 * c1 * current - previous;
                previous = current;
                current = next;
            }
        };
        // Stratified over the pixel's camera samples together (their frames
        // differ little): ray a of camera sample s in cell j is ray
        // r = a S + s of the cell's A S, at azimuth (r + rotation_j) / (A S)
        // of the turn and at mu^2 in stratum r of a scrambled radical
        // inverse; the env rays are points s, s + S, ... of a scrambled
        // Hammersley set of the pixel's N S.
        const int per_pixel = m_side * m_side;
        const int rays_per_cell = m_azimuths * per_pixel;
        for (int j = 0; j < cells; ++j) {
            for (int a = 0; a < m_azimuths; ++a) {
                const int r = a * per_pixel + sample;
                const double v = radicalInverse2(static_cast<std::uint32_t>(r),
                                                 paint.mu_scramble[static_cast<std::size_t>(j)]);
                const double mu = std::sqrt((j + v) / cells);
                const double phi =
                    2.0 * kPi * (r + paint.cell_rotation[static_cast<std::size_t>(j)]) / rays_per_cell;
                const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
                const Vec3 local(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
                add(local, j, m_env_rays > 0 ? m_residual.pdf(frame.toWorld(local)) : 0.0);
            }
        }
        const int env_per_pixel = m_env_rays * per_pixel;
        for (int k = 0; k < m_env_rays; ++k) {
            const int i = k * per_pixel + sample;
            const EnvironmentMap::Sample s =
                m_residual.sample((i + rng.uniform()) / env_per_pixel,
                                  radicalInverse2(static_cast<std::uint32_t>(i), paint.env_scramble));
            const Vec3 local = frame.toLocal(s.direction);
            if (!(local.z() > 0.0) || !(s.pdf_sr > 0.0)) continue;  // below the paint: no light
            add(local, std::min(cells - 1, static_cast<int>(local.z() * local.z() * cells)), s.pdf_sr);
        }
    }

    const PathTracer& m_pt;
    const PathTracer& m_indirect;
    const PinholeCamera& m_camera;
    const RayMapSettings& m_s;
    int m_width;
    int m_lights;
    const std::vector<DirectionalLight>& m_hotspots;
    const EnvironmentMap& m_residual;
    const EnvironmentMoments* m_environment_moments;  // null: the rays estimate L itself
    int m_side = 1;
    int m_azimuths = 4;
    int m_env_rays = 0;  // importance-sampled moment rays per camera sample
    int m_mirror_side = 2;
    int m_mirror_paths = 1;
};

}  // namespace paintlab::raymaps
