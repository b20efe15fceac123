// The precompute of a ray map (docs/RAYMAPS.md): camera rays through the
// mirrors and glass to the first other surface; the paint's records there,
// the baked radiance everywhere else.

#include "path_tracer.h"
#include "pixel_tracer.h"
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
