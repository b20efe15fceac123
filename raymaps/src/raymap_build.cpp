// The precompute of a ray map (docs/RAYMAPS.md): camera rays through the
// mirrors and glass to the first other surface; the paint's records there,
// the baked radiance everywhere else.

#include "environment_moments.h"
#include "path_tracer.h"
#include "raymap_io.h"
#include "record_layout.h"
#include "sampling.h"
#include "scene_tracer.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <Imath/half.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>

namespace paintlab::raymaps {

namespace {

void checkRange(int value, int low, int high, const char* field) {
    if (value < low || value > high)
        throw InputError("<argument>", field,
                         std::to_string(value) + " is outside [" + std::to_string(low) + ", " +
                             std::to_string(high) + "]");
}

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
        centreFrame(x, y, rng, paint);
        paint.cell_rotation.resize(static_cast<std::size_t>(m_s.cells));
        paint.mu_scramble.resize(static_cast<std::size_t>(m_s.cells));
        for (std::size_t j = 0; j < paint.cell_rotation.size(); ++j) {
            paint.cell_rotation[j] = rng.uniform();
            paint.mu_scramble[j] = rng.next();
        }
        paint.env_scramble = rng.next();
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
            paint.mirror *= inv;
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

    // The record's one frame (normal, view, position, footprint) is the
    // paint's at the pixel centre, through mirrors and the stronger branch
    // of glass as the camera samples go: the same for every seed. The
    // sample nearest the centre, used before, moved with the jitter, and the
    // explicit lights, the coat and the moments with it (~2 % per-pixel noise
    // on the sun-lit demo scene whatever the number of rays).
    void centreFrame(int x, int y, Rng& rng, PaintAccumulator& paint) const {
        paint.centred = false;
        Vec3 dir = m_camera.direction(x + 0.5, y + 0.5);
        Vec3 origin = m_camera.origin();
        double distance = 0.0;
        for (int bounce = 0;; ++bounce) {
            const Hit hit = m_pt.tracer().intersect(origin, dir);
            if (!hit.found) return;
            distance += hit.t;
            const Material& m = m_pt.material(hit);
            if (m.kind == MaterialKind::Paint) {
                setFrame(hit, dir, distance, -1.0, paint);
                paint.centred = true;
                return;
            }
            if (bounce >= m_s.max_delta_bounces) return;
            if (m.kind == MaterialKind::Mirror) {
                Rgb3 beta = Rgb3::Ones();
                dir = m_pt.deltaBounce(m, hit, dir, rng, beta);  // a mirror draws no random number
            } else if (m.kind == MaterialKind::Glass) {
                const PathTracer::GlassSplit split = m_pt.glassSplit(m, hit, dir);
                dir = split.reflectance >= 0.5 ? split.reflected : split.refracted;
            } else {
                return;
            }
            origin = m_pt.offset(hit.position, hit.geometric_normal, dir);
        }
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
        Vec3 r = reflect(wo, ns);
        if (r.dot(ng) <= 0.0) r = reflect(wo, ng);
        // What the coat mirrors: one ray, and bake_paths paths from what it
        // meets (the floor's path-traced radiance was most of this term's noise).
        const Hit mirrored = m_indirect.tracer().intersect(origin, r);
        const int paths = mirrored.found ? m_s.bake_paths : 1;
        Rgb3 mirror = Rgb3::Zero();
        for (int p = 0; p < paths; ++p) mirror += m_indirect.radianceAt(mirrored, r, rng, true);
        paint.mirror += mirror / paths;
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
};

template <typename T> void put(std::byte* at, const T& value) { std::memcpy(at, &value, sizeof(T)); }

std::uint16_t halfBits(double x) {
    // Half's largest finite value: brighter radiance saturates (a sun's disk
    // seen directly), which no display exposure distinguishes.
    constexpr double kHalfMax = 65504.0;
    return Imath::half(static_cast<float>(std::clamp(x, 0.0, kHalfMax))).bits();
}

void encodeRecord(const PaintAccumulator& p, std::uint32_t pixel, const RecordLayout& layout,
                  std::byte* out) {
    put(out + RecordLayout::kPixel, pixel);
    std::uint16_t oct[2];
    encodeOctahedral(p.normal, oct);
    std::memcpy(out + RecordLayout::kNormal, oct, 4);
    encodeOctahedral(p.view, oct);
    std::memcpy(out + RecordLayout::kView, oct, 4);
    for (int c = 0; c < 3; ++c) {
        const auto uc = static_cast<std::size_t>(c);
        put(out + RecordLayout::kPosition + 4 * uc, static_cast<float>(p.position[c]));
        put(out + RecordLayout::kWeight + 2 * uc, halfBits(p.weight[c]));
        put(out + RecordLayout::kMirror + 4 * uc, static_cast<float>(p.mirror[c]));
    }
    put(out + RecordLayout::kFootprint, halfBits(p.footprint));
    const auto orders = static_cast<std::size_t>(layout.orders);
    for (std::size_t j = 0; j < static_cast<std::size_t>(layout.cells); ++j) {
        const Rgb3& l0 = p.moments[j * orders];
        for (int c = 0; c < 3; ++c) {
            const auto uc = static_cast<std::size_t>(c);
            put(out + RecordLayout::kMoments0 + 6 * j + 2 * uc, halfBits(l0[c]));
            for (std::size_t m = 1; m < orders; ++m) {
                const double ratio = l0[c] > 0.0 ? p.moments[j * orders + m][c] / l0[c] : 0.0;
                const auto q = static_cast<std::int8_t>(std::lround(127.0 * std::clamp(ratio, -1.0, 1.0)));
                put(out + layout.momentsM() + 3 * ((orders - 1) * j + (m - 1)) + uc, q);
            }
        }
    }
    for (std::size_t k = 0; k < p.visibility.size(); ++k)
        put(out + layout.visibility() + k,
            static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(p.visibility[k], 0.0, 1.0))));
}

}  // namespace

std::size_t recordBytes(int cells, int orders, int lights) {
    return RecordLayout{cells, orders, lights}.bytes();
}

void validateRayMapSettings(const RayMapSettings& s) {
    checkRange(s.aa_samples, 1, 256, "aa_samples");
    checkRange(s.bake_paths, 1, 1024, "bake_paths");
    checkRange(s.light_rays, 1, 65536, "light_rays");
    checkRange(s.cells, 1, 16, "cells");
    checkRange(s.orders, 1, 16, "orders");
    checkRange(s.sun_shadow_rays, 1, 256, "sun_shadow_rays");
    checkRange(s.max_depth, 1, 64, "max_depth");
    checkRange(s.indirect_depth, 1, 64, "indirect_depth");
    checkRange(s.max_delta_bounces, 0, 64, "max_delta_bounces");
    checkRange(s.band_rows, 1, 4096, "band_rows");
    checkRange(s.env_lights, 0, 32, "env_lights");
    checkRange(s.environment_points, 0, 1 << 20, "environment_points");
    checkRange(s.environment_rays, 0, 65536, "environment_rays");
    if (!(s.env_light_threshold >= 1.0 && s.env_light_threshold <= 1e9))
        throw InputError("<argument>", "env_light_threshold",
                         std::to_string(s.env_light_threshold) + " is outside [1, 1e9]");
    // allFinite first: Eigen's minCoeff/maxCoeff may pass over a NaN.
    if (s.paint_proxy_albedo &&
        !(s.paint_proxy_albedo->allFinite() && s.paint_proxy_albedo->minCoeff() >= 0.0 &&
          s.paint_proxy_albedo->maxCoeff() <= 1.0))
        throw InputError("<argument>", "paint_proxy_albedo", "channels must be in [0, 1]");
    // The same range as the ray-map reader's (raymap_file.cpp): a map is never written that cannot be read.
    if (!(s.scene_unit_m >= 1e-12 && s.scene_unit_m <= 1e6))
        throw InputError("<argument>", "scene_unit_m",
                         std::to_string(s.scene_unit_m) + " is outside [1e-12, 1e6]");
}

RayMapHeader buildRayMap(const Scene& scene, const RayMapSettings& settings, const std::filesystem::path& out,
                         const RayMapProgress& progress) {
    validateRayMapSettings(settings);
    const auto start = std::chrono::steady_clock::now();
    const SceneGeometry geometry = buildSceneGeometry(scene);
    const EnvironmentMap environment = EnvironmentMap::load(scene.environment);
    const SceneTracer tracer(geometry);
    const Rgb3 proxy = settings.paint_proxy_albedo.value_or(Rgb3::Constant(kPaintProxyAlbedo));
    const PathTracer pt(scene, tracer, environment, settings.max_depth, proxy);
    const PathTracer pt_indirect(scene, tracer, environment, settings.indirect_depth, proxy);
    const PinholeCamera camera(scene.camera);

    RayMapHeader header;
    header.width = scene.camera.width;
    header.height = scene.camera.height;
    header.cells = settings.cells;
    header.orders = settings.orders;
    header.band_rows = settings.band_rows;
    header.scene_file = scene.file.filename().string();
    header.paint_proxy_albedo = proxy.mean();
    header.camera_position = camera.origin();
    header.pixel_angle_rad = camera.pixelAngle();
    header.scene_unit_m = settings.scene_unit_m;
    for (const auto& sun : pt.suns())
        header.lights.push_back({ExplicitLight::Kind::Sun, sun.direction, sun.irradiance,
                                 2.0 * kPi * (1.0 - sun.cos_half_angle)});
    for (const auto& point : pt.points())
        header.lights.push_back({ExplicitLight::Kind::Point, point.position, point.intensity, 0.0});
    // K_env: the environment's hotspots become explicit lights of the paint
    // (the bake and the mirror rays keep the whole environment).
    std::vector<EnvironmentMap::Hotspot> spots;
    const EnvironmentMap residual =
        environment.withoutHotspots(settings.env_lights, settings.env_light_threshold, spots);
    std::vector<DirectionalLight> hotspots;
    for (const auto& spot : spots) {
        const double cos_half = std::max(-1.0, 1.0 - spot.solid_angle_sr / (2.0 * kPi));
        hotspots.push_back({spot.direction, spot.irradiance, cos_half});
        header.lights.push_back(
            {ExplicitLight::Kind::Sun, spot.direction, spot.irradiance, spot.solid_angle_sr});
    }
    header.env_lights = static_cast<int>(hotspots.size());
    if (header.lights.size() > 255)
        throw InputError(scene.file.string(), "lights", "more than 255 explicit lights");
    const RecordLayout layout{settings.cells, settings.orders, static_cast<int>(header.lights.size())};

    // The header is written last (it holds the statistics), so the bands go
    // to memory first: a ray map is a few hundred bytes per paint pixel.
    const int width = header.width;
    const int bands = (header.height + settings.band_rows - 1) / settings.band_rows;
    std::vector<RayMapBand> done(static_cast<std::size_t>(bands));
    std::optional<EnvironmentMoments> environment_moments;
    if (settings.environment_points > 0) environment_moments.emplace(residual, settings.environment_points);
    const PixelTracer pixels(pt, pt_indirect, camera, settings, width, hotspots, residual,
                             environment_moments ? &*environment_moments : nullptr);
    for (int b = 0; b < bands; ++b) {
        RayMapBand& band = done[static_cast<std::size_t>(b)];
        band.first_row = b * settings.band_rows;
        band.rows = std::min(settings.band_rows, header.height - band.first_row);
        band.baked.assign(static_cast<std::size_t>(band.rows) * static_cast<std::size_t>(width) * 3, 0);
        std::vector<std::vector<std::byte>> row_records(static_cast<std::size_t>(band.rows));
        tbb::parallel_for(tbb::blocked_range<int>(0, band.rows), [&](const tbb::blocked_range<int>& range) {
            PaintAccumulator paint;
            for (int r = range.begin(); r != range.end(); ++r) {
                const int y = band.first_row + r;
                auto& records = row_records[static_cast<std::size_t>(r)];
                for (int x = 0; x < width; ++x) {
                    const Rgb3 baked = pixels.trace(x, y, paint);
                    const std::size_t at =
                        3 * (static_cast<std::size_t>(r) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x));
                    for (int c = 0; c < 3; ++c)
                        band.baked[at + static_cast<std::size_t>(c)] = halfBits(baked[c]);
                    if (paint.samples == 0) continue;
                    const std::size_t offset = records.size();
                    records.resize(offset + layout.bytes());
                    encodeRecord(paint,
                                 static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(width) +
                                     static_cast<std::uint32_t>(x),
                                 layout, records.data() + offset);
                }
            }
        });
        for (const auto& records : row_records) {
            band.records.insert(band.records.end(), records.begin(), records.end());
            band.record_count += records.size() / layout.bytes();
        }
        header.paint_pixels += band.record_count;
        if (progress && !progress(static_cast<double>(b + 1) / bands)) throw Error("cancelled");
    }
    header.rays = tracer.raysTraced();
    header.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    ChunkFileWriter writer(out, kRayMapMagic, kRayMapVersion);
    const std::string json = headerToJson(header);
    writer.addChunk(kHeaderChunk, std::as_bytes(std::span(json.data(), json.size())));
    for (const RayMapBand& band : done) {
        writer.addChunk(kBakedChunk, std::as_bytes(std::span(band.baked)));
        writer.addChunk(kPaintChunk, std::span<const std::byte>(band.records));
    }
    writer.finish();
    return header;
}

}  // namespace paintlab::raymaps
