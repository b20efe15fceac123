#pragma once
// Ray maps (docs/RAYMAPS.md): a scene traced once from its camera, with the
// final radiance of everything that is not paint baked, and for every paint
// pixel a bounded record of what shading it needs (frame, view, light
// moments, explicit-light visibility, mirror radiance). relight.h re-shades
// the paint with any LayeredBrdf in a time that depends on the image size only.
//
// File (chunk_file.h framing, magic PLRAYMAP, version 2): a header chunk
// (JSON text: image size, J cells, M_L orders, band height, the explicit
// lights, the scene file's name, the camera's position and pixel angle, the
// scene unit, the record layout's size, statistics), then
// per band of rows a BAKE chunk (baked radiance, 3 half floats per pixel) and
// a PNTR chunk (the band's paint records, recordBytes() each, layout in
// raymap.cpp). Bands are read and checked when first used. Version-1 files
// (no camera, no scene unit; the records are the same) are still read, with
// the defaults RayMapHeader documents.

#include "paintlab/raymaps/scene.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace paintlab::raymaps {

struct RayMapSettings {
    int aa_samples = 4;         // camera samples per pixel (stratified, rounded to a square)
    int bake_paths = 4;         // paths per camera sample that meets a non-paint surface
    int light_rays = 64;        // hemisphere rays per paint pixel for the light moments
    int cells = 4;              // J: cells in mu_i (equal projected solid angle)
    int orders = 4;             // M_L: azimuthal Fourier orders of the incident light
    int sun_shadow_rays = 8;    // per sun and camera sample (soft shadows of the sun's disk)
    int max_depth = 4;          // scattering path vertices of the bake (mirror/glass bounces not counted)
    int indirect_depth = 2;     // scattering path vertices behind a moment or mirror ray
    int max_delta_bounces = 8;  // mirror / glass bounces followed before the paint
    int band_rows = 32;         // rows per chunk
    // K_env: HDR hotspots (EnvironmentMap::withoutHotspots) taken out of the
    // paint's light moments and made explicit lights, at most this many,
    // brighter than env_light_threshold x the map's mean luminance.
    int env_lights = 4;
    double env_light_threshold = 50.0;
    // Points of the fixed quadrature of the environment's light moments (the
    // moment rays then estimate only what the scene changes: occlusion and
    // light from other surfaces); 0: the rays estimate all of it.
    int environment_points = 1024;
    // Moment rays per paint pixel importance sampled on the environment (in
    // addition to light_rays, which are uniform in projected solid angle).
    int environment_rays = 64;
    std::uint64_t seed = 1;
    // Passes traced by buildRayMap with seeds seed, seed + 1, ... and
    // averaged (ProgressiveRayMap): the per-pixel noise falls as 1/sqrt(passes).
    int passes = 1;
    // The Lambertian stand-in for paint that a secondary ray meets (paint
    // seen by paint in a mirror or through glass, paint lighting the floor),
    // linear sRGB albedo in [0, 1]: grey 0.35 (path_tracer.h) unless the
    // recipe is known when the map is built (render, the workstation), where
    // its diffuse albedo removes the stand-in's colour bias.
    std::optional<Rgb3> paint_proxy_albedo;
    // Metres per scene unit (scene.h: lengths are in scene units), stored in
    // the header: the sparkle pass and the effect planner turn the records'
    // footprints into µm with it. Not used by the trace itself.
    double scene_unit_m = 1.0;
};

// Throws InputError ("<argument>", field) if a setting is out of its range.
void validateRayMapSettings(const RayMapSettings& settings);

struct ExplicitLight {
    enum class Kind { Sun, Point };
    Kind kind = Kind::Sun;
    Eigen::Vector3d vector{0.0, 1.0, 0.0};  // Sun: unit direction towards it; Point: position
    Rgb3 power{1.0, 1.0, 1.0};              // Sun: irradiance W/m^2; Point: intensity W/sr
    double solid_angle_sr = 0.0;            // Sun: of its disk; Point: 0
};

struct RayMapHeader {
    int width = 0;
    int height = 0;
    int cells = 4;
    int orders = 4;
    int band_rows = 32;
    std::vector<ExplicitLight> lights;
    std::string scene_file;
    double paint_proxy_albedo = 0.0;
    int env_lights = 0;  // K_env: HDR hotspots extracted as lights (the last entries of `lights`)
    // Where the map was seen from and at what scale (file version 2), so that
    // pixel footprints, viewing distances and the viewer's aperture follow
    // from the map alone. A version-1 file reads with the defaults: camera
    // position (0, 0, 0) and pixel angle 0 (unknown: cameraKnown() is false,
    // the sparkle pass then uses a fixed viewing distance), scene unit 1 m
    // (what the CLI's --scene-unit defaulted to).
    Eigen::Vector3d camera_position{0.0, 0.0, 0.0};  // scene units
    // Width of one pixel at unit distance along the camera's axis (radians
    // per pixel at the image centre): 2 tan(vertical_fov / 2) / height. A
    // record's footprint / pixel_angle_rad is its distance along the camera
    // ray, mirror and glass bounces unfolded.
    double pixel_angle_rad = 0.0;
    double scene_unit_m = 1.0;       // metres per scene unit
    std::uint32_t file_version = 2;  // of the file read (buildRayMap writes the newest)
    bool cameraKnown() const { return pixel_angle_rad > 0.0; }
    // Statistics of the precompute.
    std::uint64_t paint_pixels = 0;
    std::uint64_t rays = 0;
    double seconds = 0.0;
};

// Bytes of one paint record for J cells, M_L orders and K lights.
std::size_t recordBytes(int cells, int orders, int lights);

struct RayMapBand {
    int first_row = 0;
    int rows = 0;
    std::vector<std::uint16_t> baked;  // half floats, rows x width x 3
    std::vector<std::byte> records;    // paint records, ascending pixel index
    std::size_t record_count = 0;
};

// An opened ray-map file. Construction reads the header and indexes the
// chunks; bands are read, checked and kept on first use.
class RayMap {
public:
    // Throws InputError naming the file (and the chunk or field) if it is
    // missing, not a ray map, of a newer version, truncated or inconsistent.
    static std::unique_ptr<RayMap> open(const std::filesystem::path& path);
    ~RayMap();
    RayMap(const RayMap&) = delete;
    RayMap& operator=(const RayMap&) = delete;
    RayMap(RayMap&&) = delete;
    RayMap& operator=(RayMap&&) = delete;

    const RayMapHeader& header() const { return m_header; }
    const std::filesystem::path& path() const;
    int bandCount() const { return static_cast<int>(m_bands.size()); }
    std::size_t recordBytes() const { return m_record_bytes; }
    // Thread safe. Throws InputError naming the file and the chunk if the
    // band is corrupt (checksum, sizes, pixel indices).
    const RayMapBand& band(int index) const;
    // Reads every band (in parallel).
    void loadAll() const;

private:
    struct Impl;
    RayMap() = default;
    RayMapHeader m_header;
    std::size_t m_record_bytes = 0;
    std::unique_ptr<Impl> m_impl;
    mutable std::vector<std::unique_ptr<RayMapBand>> m_bands;
    mutable std::vector<std::unique_ptr<std::once_flag>> m_once;
};

// Called with the fraction done (0..1); return false to cancel.
using RayMapProgress = std::function<bool(double fraction)>;

// Traces `scene` (camera, objects, environment, lights) in settings.passes
// passes (ProgressiveRayMap) and writes the ray map to `out` (atomically:
// nothing under that name unless it succeeds). Throws InputError for bad
// settings or scene content (missing files), Error("cancelled") if progress
// returns false, Error on I/O failure.
RayMapHeader buildRayMap(const Scene& scene, const RayMapSettings& settings, const std::filesystem::path& out,
                         const RayMapProgress& progress = {});

// A ray map refined pass by pass (docs/RAYMAPS.md, "Progressive refinement"):
// pass k traces the scene with seed settings.seed + k, and the map is the
// passes' average, kept at full precision in memory until written: per
// pixel the baked radiance and the paint's weight with weights k/(k+1) and
// 1/(k+1), the paint's light moments, visibility and mirror radiance by the
// camera samples that met the paint (the same for inner pixels). A record's
// frame is the pixel centre's, the same for every seed (at the paint's edge,
// the sample's nearest the centre). The per-pixel noise falls as
// 1/sqrt(passes); the file's format, size and relight time do not change.
// One pass writes the map buildRayMap writes (byte for byte but the
// statistics' seconds). settings.passes is not used here.
class ProgressiveRayMap {
public:
    // Throws InputError as buildRayMap does.
    ProgressiveRayMap(const Scene& scene, const RayMapSettings& settings);
    ~ProgressiveRayMap();
    ProgressiveRayMap(const ProgressiveRayMap&) = delete;
    ProgressiveRayMap& operator=(const ProgressiveRayMap&) = delete;
    ProgressiveRayMap(ProgressiveRayMap&&) = delete;
    ProgressiveRayMap& operator=(ProgressiveRayMap&&) = delete;

    // Traces pass passes() and averages it in; `progress` gets this pass's
    // fraction. Error("cancelled") if it returns false: the map keeps the
    // passes before.
    void addPass(const RayMapProgress& progress = {});
    int passes() const;
    // The map's layout (statistics are filled by write).
    const RayMapHeader& header() const;
    // Writes the average of the passes so far (atomically); Error if none.
    // Statistics: rays and seconds (set-up included) of all passes.
    RayMapHeader write(const std::filesystem::path& out) const;
    // Writes the average of the 1st, 3rd, 5th, ... pass alone (Error if
    // none): the other half of a noise estimate of write()'s map. With N
    // passes, n_o = ceil(N/2) of them odd and n_e = N - n_o, the full
    // average minus the odd one is (n_e / N)(even - odd), whose variance is
    // var(full) n_e / n_o: RMS(full - odd) sqrt(n_o / n_e) estimates the
    // full map's own noise (raymaps/noise_estimate.h; N >= 2).
    RayMapHeader writeOddPasses(const std::filesystem::path& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace paintlab::raymaps
