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
#include <utility>

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
    checkRange(s.passes, 1, 65536, "passes");
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

namespace {

// The passes' average of one paint pixel: `paint` holds the means (moments,
// visibility and mirror over the camera samples that met the paint, weight
// over all), `paint.samples` the samples summed over the passes.
struct PaintMean {
    int x = 0;
    PaintAccumulator paint;
};

// a += (b - a) * w, exactly b when w is 1 (the first pass).
template <typename T> void blend(T& a, const T& b, double w) {
    if (w == 1.0)
        a = b;
    else
        a += (b - a) * w;
}

// Folds one pass's pixel into the mean of the passes before it (`passes` of them).
void foldPaint(PaintAccumulator& mean, const PaintAccumulator& pass, int passes) {
    const int before = mean.samples;
    const double w = static_cast<double>(pass.samples) / (before + pass.samples);
    for (std::size_t i = 0; i < mean.moments.size(); ++i) blend(mean.moments[i], pass.moments[i], w);
    for (std::size_t k = 0; k < mean.visibility.size(); ++k) blend(mean.visibility[k], pass.visibility[k], w);
    blend(mean.mirror, pass.mirror, w);
    mean.samples = before + pass.samples;
    // The weight counts every camera sample of the pixel: a pass without paint
    // here added 0 (weights passes/(passes+1), 1/(passes+1)).
    blend(mean.weight, pass.weight, 1.0 / (passes + 1));
    // The frame nearest the pixel centre (a centred frame is the same for every seed).
    if (!mean.centred && (pass.centred || pass.frame_offset2 < mean.frame_offset2)) {
        mean.normal = pass.normal;
        mean.view = pass.view;
        mean.position = pass.position;
        mean.footprint = pass.footprint;
        mean.frame_offset2 = pass.frame_offset2;
        mean.centred = pass.centred;
    }
}

// The average of some passes: per pixel the baked radiance, per paint pixel its record's sums.
struct PassMean {
    int passes = 0;
    std::vector<Rgb3> baked;                   // row-major
    std::vector<std::vector<PaintMean>> rows;  // paint pixels per row, ascending x

    void reset(std::size_t pixels, std::size_t height) {
        baked.assign(pixels, Rgb3::Zero());
        rows.assign(height, {});
    }

    // Folds one pass (its baked radiance and paint rows) into the mean.
    void fold(const std::vector<Rgb3>& pass_baked, std::vector<std::vector<PaintMean>> pass_rows) {
        for (std::size_t i = 0; i < baked.size(); ++i) blend(baked[i], pass_baked[i], 1.0 / (passes + 1));
        tbb::parallel_for(std::size_t{0}, rows.size(), [&](std::size_t y) {
            std::vector<PaintMean>& mean = rows[y];
            std::vector<PaintMean> merged;
            merged.reserve(std::max(mean.size(), pass_rows[y].size()));
            auto a = mean.begin();
            for (PaintMean& p : pass_rows[y]) {
                for (; a != mean.end() && a->x < p.x; ++a) {
                    // No paint here in this pass: its weight is 0.
                    a->paint.weight *= static_cast<double>(passes) / (passes + 1);
                    merged.push_back(std::move(*a));
                }
                if (a != mean.end() && a->x == p.x) {
                    foldPaint(a->paint, p.paint, passes);
                    merged.push_back(std::move(*a++));
                } else {
                    // First paint here: the passes before it had none.
                    p.paint.weight *= 1.0 / (passes + 1);
                    merged.push_back(std::move(p));
                }
            }
            for (; a != mean.end(); ++a) {
                a->paint.weight *= static_cast<double>(passes) / (passes + 1);
                merged.push_back(std::move(*a));
            }
            mean = std::move(merged);
        });
        ++passes;
    }
};

}  // namespace

struct ProgressiveRayMap::Impl {
    Impl(Scene s, RayMapSettings rs)
        : scene(std::move(s)), settings(std::move(rs)), geometry(buildSceneGeometry(scene)),
          environment(EnvironmentMap::load(scene.environment)), tracer(geometry),
          proxy(settings.paint_proxy_albedo.value_or(Rgb3::Constant(kPaintProxyAlbedo))),
          pt(scene, tracer, environment, settings.max_depth, proxy),
          pt_indirect(scene, tracer, environment, settings.indirect_depth, proxy), camera(scene.camera) {}

    Scene scene;
    RayMapSettings settings;
    SceneGeometry geometry;
    EnvironmentMap environment;
    SceneTracer tracer;
    Rgb3 proxy;
    PathTracer pt;
    PathTracer pt_indirect;
    PinholeCamera camera;
    std::vector<DirectionalLight> hotspots;
    std::optional<EnvironmentMap> residual;
    std::optional<EnvironmentMoments> environment_moments;
    RayMapHeader header;
    double seconds = 0.0;  // set-up and passes
    PassMean all;          // every pass
    PassMean odd;          // the 1st, 3rd, ... pass: the noise estimate's other half (writeOddPasses)
};

ProgressiveRayMap::ProgressiveRayMap(const Scene& scene, const RayMapSettings& settings) {
    validateRayMapSettings(settings);
    const auto start = std::chrono::steady_clock::now();
    m_impl = std::make_unique<Impl>(scene, settings);
    const PathTracer& pt = m_impl->pt;
    RayMapHeader& header = m_impl->header;
    header.width = scene.camera.width;
    header.height = scene.camera.height;
    header.cells = settings.cells;
    header.orders = settings.orders;
    header.band_rows = settings.band_rows;
    header.scene_file = scene.file.filename().string();
    header.paint_proxy_albedo = m_impl->proxy.mean();
    header.camera_position = m_impl->camera.origin();
    header.pixel_angle_rad = m_impl->camera.pixelAngle();
    header.scene_unit_m = settings.scene_unit_m;
    for (const auto& sun : pt.suns())
        header.lights.push_back({ExplicitLight::Kind::Sun, sun.direction, sun.irradiance,
                                 2.0 * kPi * (1.0 - sun.cos_half_angle)});
    for (const auto& point : pt.points())
        header.lights.push_back({ExplicitLight::Kind::Point, point.position, point.intensity, 0.0});
    // K_env: the environment's hotspots become explicit lights of the paint
    // (the bake and the mirror rays keep the whole environment).
    std::vector<EnvironmentMap::Hotspot> spots;
    m_impl->residual.emplace(
        m_impl->environment.withoutHotspots(settings.env_lights, settings.env_light_threshold, spots));
    for (const auto& spot : spots) {
        const double cos_half = std::max(-1.0, 1.0 - spot.solid_angle_sr / (2.0 * kPi));
        m_impl->hotspots.push_back({spot.direction, spot.irradiance, cos_half});
        header.lights.push_back(
            {ExplicitLight::Kind::Sun, spot.direction, spot.irradiance, spot.solid_angle_sr});
    }
    header.env_lights = static_cast<int>(m_impl->hotspots.size());
    if (header.lights.size() > 255)
        throw InputError(scene.file.string(), "lights", "more than 255 explicit lights");
    if (settings.environment_points > 0)
        m_impl->environment_moments.emplace(*m_impl->residual, settings.environment_points);
    const std::size_t pixels =
        static_cast<std::size_t>(header.width) * static_cast<std::size_t>(header.height);
    m_impl->all.reset(pixels, static_cast<std::size_t>(header.height));
    m_impl->odd.reset(pixels, static_cast<std::size_t>(header.height));
    m_impl->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ProgressiveRayMap::~ProgressiveRayMap() = default;

int ProgressiveRayMap::passes() const { return m_impl->all.passes; }

const RayMapHeader& ProgressiveRayMap::header() const { return m_impl->header; }

void ProgressiveRayMap::addPass(const RayMapProgress& progress) {
    const auto start = std::chrono::steady_clock::now();
    RayMapSettings settings = m_impl->settings;
    settings.seed = m_impl->settings.seed + static_cast<std::uint64_t>(m_impl->all.passes);
    const int width = m_impl->header.width;
    const int height = m_impl->header.height;
    const int band_rows = settings.band_rows;
    const int bands = (height + band_rows - 1) / band_rows;
    const PixelTracer pixels(m_impl->pt, m_impl->pt_indirect, m_impl->camera, settings, width,
                             m_impl->hotspots, *m_impl->residual,
                             m_impl->environment_moments ? &*m_impl->environment_moments : nullptr);
    // The pass is traced aside and folded in at the end: a cancelled pass
    // leaves the map as it was.
    std::vector<Rgb3> baked(m_impl->all.baked.size());
    std::vector<std::vector<PaintMean>> rows(m_impl->all.rows.size());
    for (int b = 0; b < bands; ++b) {
        const int first = b * band_rows;
        const int count = std::min(band_rows, height - first);
        tbb::parallel_for(tbb::blocked_range<int>(first, first + count),
                          [&](const tbb::blocked_range<int>& range) {
                              PaintAccumulator paint;
                              for (int y = range.begin(); y != range.end(); ++y) {
                                  auto& row = rows[static_cast<std::size_t>(y)];
                                  for (int x = 0; x < width; ++x) {
                                      baked[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                            static_cast<std::size_t>(x)] = pixels.trace(x, y, paint);
                                      if (paint.samples > 0) row.push_back({x, paint});
                                  }
                              }
                          });
        if (progress && !progress(static_cast<double>(b + 1) / bands)) throw Error("cancelled");
    }
    if (m_impl->all.passes % 2 == 0) m_impl->odd.fold(baked, rows);  // a copy of the rows
    m_impl->all.fold(baked, std::move(rows));
    m_impl->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// Writes `mean` (atomically) with `header`'s layout and statistics; sets its paint_pixels.
RayMapHeader writeMean(const PassMean& mean, RayMapHeader header, int band_rows,
                       const std::filesystem::path& out) {
    if (mean.passes == 0) throw Error("ray map " + out.string() + ": no pass traced");
    const RecordLayout layout{header.cells, header.orders, static_cast<int>(header.lights.size())};
    const int width = header.width;
    const int bands = (header.height + band_rows - 1) / band_rows;
    std::vector<RayMapBand> done(static_cast<std::size_t>(bands));
    tbb::parallel_for(0, bands, [&](int b) {
        RayMapBand& band = done[static_cast<std::size_t>(b)];
        band.first_row = b * band_rows;
        band.rows = std::min(band_rows, header.height - band.first_row);
        const std::size_t first = static_cast<std::size_t>(band.first_row) * static_cast<std::size_t>(width);
        band.baked.resize(static_cast<std::size_t>(band.rows) * static_cast<std::size_t>(width) * 3);
        for (std::size_t i = 0; i < band.baked.size() / 3; ++i)
            for (int c = 0; c < 3; ++c)
                band.baked[3 * i + static_cast<std::size_t>(c)] = halfBits(mean.baked[first + i][c]);
        for (int y = band.first_row; y < band.first_row + band.rows; ++y)
            for (const PaintMean& p : mean.rows[static_cast<std::size_t>(y)]) {
                const std::size_t offset = band.records.size();
                band.records.resize(offset + layout.bytes());
                encodeRecord(p.paint,
                             static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(width) +
                                 static_cast<std::uint32_t>(p.x),
                             layout, band.records.data() + offset);
                ++band.record_count;
            }
    });
    header.paint_pixels = 0;
    for (const RayMapBand& band : done) header.paint_pixels += band.record_count;

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

}  // namespace

RayMapHeader ProgressiveRayMap::write(const std::filesystem::path& out) const {
    RayMapHeader header = m_impl->header;
    header.rays = m_impl->tracer.raysTraced();
    header.seconds = m_impl->seconds;
    return writeMean(m_impl->all, header, m_impl->settings.band_rows, out);
}

RayMapHeader ProgressiveRayMap::writeOddPasses(const std::filesystem::path& out) const {
    RayMapHeader header = m_impl->header;
    header.rays = m_impl->tracer.raysTraced();
    header.seconds = m_impl->seconds;
    return writeMean(m_impl->odd, header, m_impl->settings.band_rows, out);
}

RayMapHeader buildRayMap(const Scene& scene, const RayMapSettings& settings, const std::filesystem::path& out,
                         const RayMapProgress& progress) {
    ProgressiveRayMap map(scene, settings);
    for (int k = 0; k < settings.passes; ++k)
        map.addPass([&](double f) { return !progress || progress((k + f) / settings.passes); });
    return map.write(out);
}

}  // namespace paintlab::raymaps
