// Ray maps: precompute, file and relight against independent truths (the
// BRDF's own albedo and eval(), energy), determinism, and the rejection of
// corrupt or truncated files.

#include "temp_dir.h"
#include "write_exr.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/chunk_file.h"
#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/paint_proxy.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/reference.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace paintlab::raymaps {
namespace {

const std::filesystem::path kData = std::filesystem::path(PAINTLAB_RAYMAPS_TEST_DATA_DIR);

LayeredBrdf brdfOf(const std::filesystem::path& recipe) {
    return computeLayeredBrdf(loadRecipeFile(recipe), presetSettings(Preset::Preview));
}

// A lat-long EXR of constant radiance.
std::filesystem::path writeUniformSky(const test::TempDir& dir, float radiance) {
    const auto path = dir.path() / "uniform.exr";
    const int w = 16;
    const int h = 8;
    std::vector<float> rgb(static_cast<std::size_t>(w * h * 3), radiance);
    return test::writeExr(path, w, h, rgb);
}

// A paint sphere of radius 1 at the origin, seen from +z, nothing else.
std::string sphereScene(const std::filesystem::path& sky, int size) {
    return R"({"schema_version": 1,
      "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "vertical_fov_deg": 35, "width": )" +
           std::to_string(size) + R"(, "height": )" + std::to_string(size) + R"(},
      "environment": {"file": ")" +
           sky.string() + R"("},
      "materials": [{"name": "paint", "kind": "paint"}],
      "objects": [{"name": "ball", "sphere": {"radius": 1, "subdivisions": 5}, "material": "paint"}]})";
}

RayMapSettings smallSettings() {
    RayMapSettings s;
    s.aa_samples = 1;
    s.light_rays = 16;
    s.bake_paths = 1;
    s.sun_shadow_rays = 4;
    s.band_rows = 8;
    return s;
}

Rgb3 pixel(const RgbImage& image, int x, int y) {
    const auto i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                        static_cast<std::size_t>(x));
    return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

// Under a uniform environment L a convex body sees L in every direction,
// so its radiance is L x albedo(wo) (reciprocity), whatever its shape.
// With a uniform sky every moment ray returns exactly L: l^0_j = L pi / J,
// and l^m (m >= 1) vanish exactly because the azimuths of each cell are
// equally spaced (sum_a cos(m phi_a) = 0 for 0 < m < count); no order is
// truncated, and sum_j fbar^0_j l^0_j = 2 pi L int a_0 mu dmu = L albedo.
// What remains: half-float storage (5e-4), the 8-point Gauss rule per cell
// and the fast model's own quadrature behind albedo() (1e-3 together for
// this flat BRDF), linear interpolation in mu_o (the albedo is flat to 1e-4
// here), and the pixel's sample not being at its centre. Budget 0.5 %.
TEST(RayMap, ConvexLambertianUnderUniformSkyShowsAlbedoTimesRadiance) {
    const test::TempDir dir;
    const float sky_radiance = 0.8F;
    const int size = 24;
    const Scene scene = parseSceneJson(sphereScene(writeUniformSky(dir, sky_radiance), size), "sphere.json");
    const auto map_path = dir.path() / "sphere.prm";
    const RayMapHeader built = buildRayMap(scene, smallSettings(), map_path);
    EXPECT_GT(built.paint_pixels, 100U);

    const auto map = RayMap::open(map_path);
    const LayeredBrdf brdf = brdfOf(kData / "lambertian_index_matched.json");
    const RelightTables tables(brdf, map->header().cells, map->header().orders);
    const RgbImage image = relight(*map, tables);
    const double camera_z = 4.0;
    const double half_height = std::tan(0.5 * 35.0 * std::numbers::pi / 180.0);
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            // The pixel centre's ray and its hit on the unit sphere.
            const Eigen::Vector3d d = Eigen::Vector3d((2.0 * (x + 0.5) - size) / size * half_height,
                                                      (size - 2.0 * (y + 0.5)) / size * half_height, -1.0)
                                          .normalized();
            const Eigen::Vector3d o(0, 0, camera_z);
            const double b = o.dot(d);
            const double disc = b * b - (o.squaredNorm() - 1.0);
            // Only pixels well inside the silhouette (every sample on the paint).
            if (disc < 0.15) continue;
            const Eigen::Vector3d p = o + (-b - std::sqrt(disc)) * d;
            const double mu_o = std::clamp(p.normalized().dot(-d), 0.0, 1.0);
            const Direction wo{std::sqrt(1.0 - mu_o * mu_o), 0.0, mu_o};
            const Rgb3 expected = tables.toRgb(brdf.albedo(wo)) * sky_radiance;
            const Rgb3 got = pixel(image, x, y);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(got[c], expected[c], 5e-3 * expected[c])
                    << "pixel " << x << ", " << y << " channel " << c;
                worst = std::max(worst, std::abs(got[c] - expected[c]) / expected[c]);
            }
            ++checked;
        }
    EXPECT_GT(checked, 100);
    std::printf("%d paint pixels, largest relative error %.2e\n", checked, worst);
    // And the background is the sky itself.
    EXPECT_NEAR(pixel(image, 0, 0).x(), sky_radiance, 1e-3);
}

// A plane lit by a sun alone (black sky), seen from far away through a
// narrow field so that wo is the same at every pixel to 0.15 degrees:
// L = f_rgb(wi, wo) E cos(theta_i) with f from the BRDF's own eval().
// The explicit-light path adds only the light table's trilinear
// interpolation (spacing 1/32 in mu, 1/16 in cos dphi) and half floats;
// the flake paint's lobe is ~25 degrees wide, so the interpolation error
// h^2 f''/8 stays below 1 % (measured: 0.5 % worst pixel). Budget 1.5 %.
TEST(RayMap, SunLitPlaneMatchesBrdfTimesIrradianceTimesCosine) {
    const test::TempDir dir;
    const Eigen::Vector3d sun = Eigen::Vector3d(0.4, 0.8, -0.3).normalized();
    const Eigen::Vector3d eye(0.0, 300.0, 400.0);
    const std::string text = R"({"schema_version": 1,
      "camera": {"position": [0, 300, 400], "look_at": [0, 0, 0], "vertical_fov_deg": 0.3, "width": 12, "height": 12},
      "environment": {"intensity": 0},
      "lights": [{"type": "sun", "direction": [0.4, 0.8, -0.3], "irradiance": [2, 3, 4]}],
      "materials": [{"name": "paint", "kind": "paint"}],
      "objects": [{"name": "panel", "plane": {"size": 20}, "material": "paint"}]})";
    const Scene scene = parseSceneJson(text, "panel.json");
    const auto map_path = dir.path() / "panel.prm";
    buildRayMap(scene, smallSettings(), map_path);
    const auto map = RayMap::open(map_path);
    ASSERT_EQ(map->header().lights.size(), 1U);
    const LayeredBrdf brdf = brdfOf(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
    const RelightTables tables(brdf, map->header().cells, map->header().orders);
    const RgbImage image = relight(*map, tables);

    // Local frame of the plane: z = +y (normal), x = +x, y = -z (right-handed).
    const auto local = [](const Eigen::Vector3d& w) { return Direction{w.x(), -w.z(), w.y()}; };
    const Eigen::Vector3d wo = eye.normalized();
    const Rgb3 f = tables.toRgb(brdf.eval(local(sun), local(wo)));
    const Rgb3 expected = f.cwiseProduct(Rgb3(2, 3, 4)) * sun.y();
    double worst = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(pixel(image, x, y)[c], expected[c], 1.5e-2 * expected[c])
                    << "pixel " << x << ", " << y << " channel " << c;
                worst = std::max(worst, std::abs(pixel(image, x, y)[c] - expected[c]) / expected[c]);
            }
    std::printf("largest relative error %.2e\n", worst);
}

// The light table against eval() at off-grid points of a flake paint: the
// same interpolation budget as above, here over the whole hemisphere away
// from grazing angles (where f itself varies fastest).
TEST(RelightTables, LightTableMatchesEvalWithinInterpolationError) {
    const LayeredBrdf brdf = brdfOf(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
    const RelightTables tables(brdf, 4, 4);
    double worst = 0.0;
    for (double theta_o : {7.0, 23.0, 41.0, 58.0})
        for (double theta_i : {11.0, 29.0, 47.0, 63.0})
            for (double phi : {0.0, 37.0, 95.0, 170.0}) {
                const Direction wi = directionFromAnglesDeg(theta_i, phi);
                const Direction wo = directionFromAnglesDeg(theta_o, 0.0);
                const Rgb3 f = tables.toRgb(brdf.eval(wi, wo));
                const Rgb3 t = tables.lightTable(wo.z, wi.z, std::cos(phi * std::numbers::pi / 180.0));
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(t[c] - f[c]) / f[c]);
            }
    std::printf("largest relative error of the light table: %.2e\n", worst);
    EXPECT_LT(worst, 1.5e-2);
}

// The same pixels come out for one thread and for two: every pixel draws
// its own random numbers.
TEST(RayMap, OutputDoesNotDependOnTheThreadCount) {
    const test::TempDir dir;
    const Scene scene = parseSceneJson(sphereScene(writeUniformSky(dir, 1.0F), 16), "sphere.json");
    RayMapSettings s = smallSettings();
    std::vector<std::vector<float>> images;
    for (int threads : {1, 2}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(threads));
        const auto path = dir.path() / ("t" + std::to_string(threads) + ".prm");
        buildRayMap(scene, s, path);
        const auto map = RayMap::open(path);
        const LayeredBrdf brdf = brdfOf(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
        images.push_back(relight(*map, RelightTables(brdf, 4, 4)).rgb);
    }
    ASSERT_EQ(images[0].size(), images[1].size());
    EXPECT_TRUE(images[0] == images[1]);
}

class RayMapFile : public ::testing::Test {
protected:
    void SetUp() override {
        const Scene scene = parseSceneJson(sphereScene(writeUniformSky(m_dir, 1.0F), 16), "sphere.json");
        m_path = m_dir.path() / "map.prm";
        buildRayMap(scene, smallSettings(), m_path);
    }
    std::vector<char> bytes() const {
        std::ifstream in(m_path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    void write(const std::vector<char>& data) const {
        std::ofstream(m_path, std::ios::binary | std::ios::trunc)
            .write(data.data(), static_cast<std::streamsize>(data.size()));
    }
    test::TempDir m_dir;
    std::filesystem::path m_path;
};

TEST_F(RayMapFile, ReportsItsLayout) {
    const auto map = RayMap::open(m_path);
    EXPECT_EQ(map->header().width, 16);
    EXPECT_EQ(map->bandCount(), 2);
    // J = 4, M_L = 4, no light: 44 + 24 + 36 bytes (docs/RAYMAPS.md).
    EXPECT_EQ(map->recordBytes(), 104U);
    map->loadAll();
    EXPECT_EQ(map->band(0).record_count + map->band(1).record_count, map->header().paint_pixels);
}

TEST_F(RayMapFile, CorruptPaintRecordIsRejectedNamingFileAndChunk) {
    std::vector<char> data = bytes();
    // The last PNTR chunk ends 32 bytes before the file's end (the end chunk
    // is a 24-byte header + 8 bytes); flip a byte inside it.
    data[data.size() - 32 - 50] ^= 0x10;
    write(data);
    const auto map = RayMap::open(m_path);  // only chunk headers are read here
    try {
        map->loadAll();
        FAIL() << "a corrupt paint chunk was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(m_path.string()), std::string::npos) << what;
        EXPECT_NE(what.find("PNTR"), std::string::npos) << what;
        EXPECT_NE(what.find("checksum"), std::string::npos) << what;
    }
}

TEST_F(RayMapFile, TruncatedFileIsRejectedNamingTheFile) {
    std::vector<char> data = bytes();
    data.resize(data.size() * 2 / 3);
    write(data);
    try {
        (void)RayMap::open(m_path);
        FAIL() << "a truncated ray map was opened";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(m_path.string()), std::string::npos) << what;
        EXPECT_NE(what.find("truncated"), std::string::npos) << what;
    }
}

TEST_F(RayMapFile, OtherFileIsRejected) {
    std::vector<char> data = bytes();
    data[0] = 'X';
    write(data);
    EXPECT_THROW((void)RayMap::open(m_path), InputError);
}

// Rewrites the map as format `version` with its header JSON changed by `edit`
// (chunk_file.h's framing: the same chunks, in the same order).
template <typename Edit> void rewriteMap(const std::filesystem::path& from, const std::filesystem::path& to,
                                         std::uint32_t version, Edit edit) {
    const Magic magic{'P', 'L', 'R', 'A', 'Y', 'M', 'A', 'P'};
    const ChunkFileReader reader(from, magic, 2);
    std::vector<std::vector<std::byte>> payloads;
    for (std::size_t i = 0; i < reader.chunks().size(); ++i) payloads.push_back(reader.read(i));
    const std::vector<std::byte>& head = payloads[0];
    nlohmann::json j =
        nlohmann::json::parse(std::string(reinterpret_cast<const char*>(head.data()), head.size()));
    edit(j);
    const std::string text = j.dump();
    payloads[0].resize(text.size());
    std::memcpy(payloads[0].data(), text.data(), text.size());
    ChunkFileWriter writer(to, magic, version);
    for (std::size_t i = 0; i < payloads.size(); ++i)
        writer.addChunk(reader.chunks()[i].type, std::span<const std::byte>(payloads[i]));
    writer.finish();
}

// Version 2: where the map was seen from and at what scale, for footprints
// and viewing distances from the map alone (sparkle, the effect planner).
TEST_F(RayMapFile, HeaderHoldsTheCameraAndTheSceneUnit) {
    const auto map = RayMap::open(m_path);
    const RayMapHeader& h = map->header();
    EXPECT_EQ(h.file_version, 2U);
    EXPECT_TRUE(h.cameraKnown());
    EXPECT_NEAR((h.camera_position - Eigen::Vector3d(0, 0, 4)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(h.pixel_angle_rad, 2.0 * std::tan(0.5 * 35.0 * std::numbers::pi / 180.0) / 16.0, 1e-12);
    EXPECT_EQ(h.scene_unit_m, 1.0);
    // A record's footprint / pixel angle is its distance from the camera:
    // the sphere's front is 3 units away.
    map->loadAll();
    const PaintSample sample = decodePaintSample(*map, map->band(0), map->band(0).record_count - 1);
    const double distance = (sample.position.cast<double>() - h.camera_position).norm();
    EXPECT_NEAR(static_cast<double>(sample.footprint) / h.pixel_angle_rad, distance,
                2e-3 * distance);  // half-float footprint

    const Scene scene = parseSceneJson(sphereScene(writeUniformSky(m_dir, 1.0F), 16), "sphere.json");
    RayMapSettings mm = smallSettings();
    mm.scene_unit_m = 1e-3;
    buildRayMap(scene, mm, m_dir.path() / "mm.prm");
    EXPECT_EQ(RayMap::open(m_dir.path() / "mm.prm")->header().scene_unit_m, 1e-3);
}

// Maps written before version 2 (no camera, no scene unit; the same
// records) are read with the documented defaults and relight the same.
TEST_F(RayMapFile, VersionOneFileIsReadWithDefaults) {
    const auto v1 = m_dir.path() / "v1.prm";
    rewriteMap(m_path, v1, 1, [](nlohmann::json& j) {
        j.erase("camera");
        j.erase("scene_unit_m");
    });
    const auto old_map = RayMap::open(v1);
    const RayMapHeader& h = old_map->header();
    EXPECT_EQ(h.file_version, 1U);
    EXPECT_FALSE(h.cameraKnown());
    EXPECT_EQ(h.pixel_angle_rad, 0.0);
    EXPECT_EQ(h.scene_unit_m, 1.0);
    const auto new_map = RayMap::open(m_path);
    EXPECT_EQ(h.paint_pixels, new_map->header().paint_pixels);
    const LayeredBrdf brdf = brdfOf(kData / "lambertian_index_matched.json");
    const RelightTables tables(brdf, h.cells, h.orders);
    EXPECT_EQ(relight(*old_map, tables).rgb, relight(*new_map, tables).rgb);
}

TEST_F(RayMapFile, VersionTwoHeaderWithoutCameraIsRejectedNamingTheField) {
    const auto bad = m_dir.path() / "bad.prm";
    rewriteMap(m_path, bad, 2, [](nlohmann::json& j) { j.erase("camera"); });
    try {
        (void)RayMap::open(bad);
        FAIL() << "a version-2 header without the camera was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(bad.string()), std::string::npos) << what;
        EXPECT_NE(what.find("camera"), std::string::npos) << what;
    }
    rewriteMap(m_path, bad, 2, [](nlohmann::json& j) { j["camera"]["pixel_angle_rad"] = -1.0; });
    EXPECT_THROW((void)RayMap::open(bad), InputError);
    // A version-1 file cannot carry version-2 fields (unknown keys are errors).
    rewriteMap(m_path, bad, 1, [](nlohmann::json&) {});
    EXPECT_THROW((void)RayMap::open(bad), InputError);
}

TEST_F(RayMapFile, NewerVersionIsRejectedSayingWhatThisBuildReads) {
    const auto newer = m_dir.path() / "v3.prm";
    rewriteMap(m_path, newer, 3, [](nlohmann::json&) {});
    try {
        (void)RayMap::open(newer);
        FAIL() << "a version-3 map was opened";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("version 3"), std::string::npos) << what;
        EXPECT_NE(what.find("versions 1 to 2"), std::string::npos) << what;
    }
}

TEST(RayMap, BadSettingsAreInputErrors) {
    RayMapSettings s;
    s.cells = 0;
    EXPECT_THROW(validateRayMapSettings(s), InputError);
    s = RayMapSettings{};
    s.orders = 40;
    EXPECT_THROW(validateRayMapSettings(s), InputError);
    s = RayMapSettings{};
    s.paint_proxy_albedo = Rgb3(0.5, std::nan(""), 0.5);
    EXPECT_THROW(validateRayMapSettings(s), InputError);
    s.paint_proxy_albedo = Rgb3(0.5, 1.5, 0.5);
    EXPECT_THROW(validateRayMapSettings(s), InputError);
    s = RayMapSettings{};
    s.scene_unit_m = 0.0;
    EXPECT_THROW(validateRayMapSettings(s), InputError);
}

// The stand-in for paint met by secondary rays has the recipe's colour: the
// red test paint (iron-oxide-like pigment) reflects red several times more
// than green or blue, and every channel is a valid albedo.
TEST(RayMap, PaintProxyHasTheRecipeColour) {
    const LayeredBrdf brdf = brdfOf(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
    const Rgb3 proxy = paintProxyAlbedo(brdf);
    EXPECT_GE(proxy.minCoeff(), 0.0);
    EXPECT_LE(proxy.maxCoeff(), 1.0);
    EXPECT_GT(proxy.x(), 2.0 * proxy.y());
    EXPECT_GT(proxy.x(), 2.0 * proxy.z());
}

TEST(RayMap, CancelledBuildLeavesNoFile) {
    const test::TempDir dir;
    const Scene scene = parseSceneJson(sphereScene(writeUniformSky(dir, 1.0F), 16), "sphere.json");
    const auto path = dir.path() / "cancelled.prm";
    EXPECT_THROW(buildRayMap(scene, smallSettings(), path, [](double) { return false; }), Error);
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace paintlab::raymaps

namespace paintlab::raymaps {
namespace {

// Relight against the brute-force reference (reference.h: the same RGB BRDF
// and clear-coat term, traced with no ray-map approximation) on a flake
// paint sphere on a grey floor under the built-in sky and a sun. Compared:
// the mean over the sphere's interior pixels (per channel), where the
// reference's noise is known (sum of its per-pixel variances of the mean).
// Budget: 3 % (the issue's goal is 2 % RMSE; here the moments' truncation
// at J = 4, M_L = 4 of the sky and floor, the paint proxy for light the
// sphere sends to the floor and back, and the relight tables'
// interpolation), plus 4 standard errors of the reference.
// `lighting`: the scene's "lights" and "environment" members (JSON).
void expectRelightMatchesReference(const test::TempDir& dir, const std::string& lighting,
                                   int expected_env_lights, const std::filesystem::path& recipe) {
    const int size = 32;
    const std::string text = R"({"schema_version": 1,
      "camera": {"position": [0, 1, 4], "look_at": [0, 0.8, 0], "vertical_fov_deg": 30, "width": 32, "height": 32},
      )" + lighting + R"(,
      "materials": [{"name": "paint", "kind": "paint"}, {"name": "ground", "kind": "diffuse", "albedo": [0.4, 0.4, 0.4]}],
      "objects": [{"name": "ball", "sphere": {"radius": 0.8, "subdivisions": 5}, "material": "paint",
                   "transform": {"translate": [0, 0.8, 0]}},
                  {"name": "floor", "plane": {"size": 30}, "material": "ground"}]})";
    const Scene scene = parseSceneJson(text, "sphere_sun.json");
    RayMapSettings s = smallSettings();
    s.light_rays = 64;
    const auto map_path = dir.path() / "sphere_sun.prm";
    buildRayMap(scene, s, map_path);
    const auto map = RayMap::open(map_path);
    EXPECT_EQ(map->header().env_lights, expected_env_lights);
    const LayeredBrdf brdf = brdfOf(recipe);
    const RelightTables tables(brdf, map->header().cells, map->header().orders);
    const RgbImage relit = relight(*map, tables);
    ReferenceSettings rs;
    rs.samples_per_pixel = 512;
    const ReferenceImage reference = renderReference(scene, tables, rs);

    // Interior pixels of the sphere: the pixel-centre ray passes 0.1 radius
    // inside the silhouette.
    const Eigen::Vector3d eye(0, 1, 4);
    const Eigen::Vector3d forward = (Eigen::Vector3d(0, 0.8, 0) - eye).normalized();
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = right.cross(forward);
    const double half = std::tan(15.0 * std::numbers::pi / 180.0);
    const Eigen::Vector3d centre(0, 0.8, 0);
    Rgb3 sum_relit = Rgb3::Zero();
    Rgb3 sum_reference = Rgb3::Zero();
    Rgb3 variance = Rgb3::Zero();
    int count = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Eigen::Vector3d d = (forward + (2.0 * (x + 0.5) - size) / size * half * right +
                                       (size - 2.0 * (y + 0.5)) / size * half * up)
                                          .normalized();
            const Eigen::Vector3d oc = eye - centre;
            const double b = oc.dot(d);
            const double distance2 = oc.squaredNorm() - b * b;  // squared distance of the ray from the centre
            if (distance2 > 0.7 * 0.7) continue;
            const std::size_t at = 3 * (static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x));
            for (int c = 0; c < 3; ++c) {
                sum_relit[c] += static_cast<double>(relit.rgb[at + static_cast<std::size_t>(c)]);
                sum_reference[c] += static_cast<double>(reference.mean.rgb[at + static_cast<std::size_t>(c)]);
                variance[c] +=
                    static_cast<double>(reference.variance_of_mean[at + static_cast<std::size_t>(c)]);
            }
            ++count;
        }
    ASSERT_GT(count, 100);
    for (int c = 0; c < 3; ++c) {
        const double sigma = std::sqrt(variance[c]);
        const double diff = sum_relit[c] - sum_reference[c];
        std::printf(
            "channel %d: relit %.4f, reference %.4f +- %.4f (mean per pixel), relative difference %.2f %%\n",
            c, sum_relit[c] / count, sum_reference[c] / count, sigma / count,
            100.0 * diff / sum_reference[c]);
        EXPECT_LT(std::abs(diff), 0.03 * sum_reference[c] + 4.0 * sigma) << "channel " << c;
    }
}

TEST(Reference, RelightMatchesTheBruteForceReferenceOnASunLitSphere) {
    const test::TempDir dir;
    expectRelightMatchesReference(
        dir, R"("lights": [{"type": "sun", "direction": [0.5, 0.8, 0.6], "irradiance": [2, 2, 2]}])", 0,
        std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
}

// A lat-long sky (0.3 above, 0.1 below the horizon) with a 2 x 2-pixel
// hotspot of radiance 3000 near (0.5, 0.8, 0.6): K_env takes it out of the
// moments (where M_L = 4 orders would smear it over the hemisphere) and
// makes it an explicit light; the reference keeps it in the environment
// (importance sampled). Same budget as above. The paint here has no clear
// coat (the Lambertian-like test recipe): the coat's mirror image of a
// radiance-3000 spot is a delta path the reference can only hit by chance,
// which made its noise (7 % per pixel mean) larger than the budget.
std::filesystem::path writeSkyWithHotspot(const test::TempDir& dir) {
    const int w = 64;
    const int h = 32;
    std::vector<float> rgb(static_cast<std::size_t>(w * h * 3));
    for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) {
            const bool spot = (u == 24 || u == 25) && (v == 7 || v == 8);
            const float value = spot ? 3000.0F : (v < h / 2 ? 0.3F : 0.1F);
            for (int c = 0; c < 3; ++c) rgb[static_cast<std::size_t>((v * w + u) * 3 + c)] = value;
        }
    return test::writeExr(dir.path() / "hotspot.exr", w, h, rgb);
}

TEST(Reference, RelightMatchesTheReferenceUnderAnHdrWithAHotspot) {
    const test::TempDir dir;
    expectRelightMatchesReference(
        dir, R"("environment": {"file": ")" + writeSkyWithHotspot(dir).string() + R"("})", 1,
        kData / "lambertian_index_matched.json");
}

// Extraction conserves the environment's power: residual + hotspot = map
// (luminance integral; the hotspot's irradiance is its excess radiance
// times the pixels' solid angles, the same measure). Float storage: 1e-6.
TEST(EnvironmentHotspots, ResidualPlusHotspotsIsTheMap) {
    const test::TempDir dir;
    const EnvironmentMap map = EnvironmentMap::load(Environment{writeSkyWithHotspot(dir), 0.0, 1.0});
    std::vector<EnvironmentMap::Hotspot> spots;
    const EnvironmentMap residual = map.withoutHotspots(4, 50.0, spots);
    ASSERT_EQ(spots.size(), 1U);  // the sky itself is nowhere 50 x its mean
    EXPECT_NEAR(residual.luminanceIntegral() + luminance(spots[0].irradiance), map.luminanceIntegral(),
                1e-6 * map.luminanceIntegral());
    // Its direction is the centre of the four pixels (u = 25, v = 8 in pixel units).
    const double phi = 2.0 * std::numbers::pi * 25.0 / 64.0;
    const double theta = std::numbers::pi * 8.0 / 32.0;
    const Eigen::Vector3d expected(std::sin(theta) * std::sin(phi), std::cos(theta),
                                   -std::sin(theta) * std::cos(phi));
    EXPECT_GT(spots[0].direction.dot(expected), std::cos(0.5 * std::numbers::pi / 180.0));
    // The residual there is the surrounding sky.
    EXPECT_NEAR(residual.radiance(expected).x(), 0.3, 1e-3);
}

}  // namespace
}  // namespace paintlab::raymaps
