// Scene files: what a valid file gives, and a clear error naming the field
// for every kind of bad input.

#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/scene.h"

#include <gtest/gtest.h>

#include <string>

namespace paintlab::raymaps {
namespace {

const std::string kMinimal = R"({
  "schema_version": 1,
  "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "width": 64, "height": 32},
  "materials": [{"name": "paint", "kind": "paint"},
                {"name": "ground", "kind": "diffuse", "albedo": [0.5, 0.4, 0.3]}],
  "objects": [{"name": "ball", "sphere": {"radius": 0.5}, "material": "paint",
               "transform": {"translate": [0, 0.5, 0]}},
              {"name": "floor", "plane": {"size": 20}, "material": "ground"}],
  "lights": [{"type": "sun", "direction": [1, 1, 0], "irradiance": [800, 780, 760]}]
})";

// Replaces the first occurrence of `from` in the minimal scene.
std::string edited(const std::string& from, const std::string& to) {
    std::string text = kMinimal;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    return text;
}

// The error must name the field (and the source): labs fix files by these messages.
void expectError(const std::string& text, const std::string& field_part, const std::string& message_part) {
    try {
        (void)parseSceneJson(text, "scene.json");
        FAIL() << "accepted a bad scene; expected an error about " << field_part;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("scene.json"), std::string::npos) << what;
        EXPECT_NE(what.find(field_part), std::string::npos) << what;
        EXPECT_NE(what.find(message_part), std::string::npos) << what;
    }
}

TEST(SceneJson, ReadsTheMinimalScene) {
    const Scene scene = parseSceneJson(kMinimal, "scene.json");
    EXPECT_EQ(scene.camera.width, 64);
    EXPECT_EQ(scene.camera.height, 32);
    EXPECT_DOUBLE_EQ(scene.camera.vertical_fov_deg, 40.0);  // default
    ASSERT_EQ(scene.materials.size(), 2U);
    EXPECT_EQ(scene.materials[0].kind, MaterialKind::Paint);
    EXPECT_DOUBLE_EQ(scene.materials[1].albedo.y(), 0.4);
    ASSERT_EQ(scene.objects.size(), 2U);
    EXPECT_DOUBLE_EQ(std::get<SphereShape>(scene.objects[0].shape).radius, 0.5);
    EXPECT_EQ(scene.materialIndex("ground"), 1);
    EXPECT_EQ(scene.materialIndex("nope"), -1);
    ASSERT_EQ(scene.lights.size(), 1U);
    const auto& sun = std::get<SunLight>(scene.lights[0]);
    EXPECT_NEAR(sun.direction.norm(), 1.0, 1e-15);  // normalised on load
    EXPECT_TRUE(scene.environment.file.empty());    // built-in sky
}

TEST(SceneJson, TransformAppliesScaleRotationTranslation) {
    Transform t;
    t.scale = 2.0;
    t.rotate_deg = {0.0, 90.0, 0.0};
    t.translate = {1.0, 0.0, 0.0};
    const Eigen::Vector4d p = t.matrix() * Eigen::Vector4d(1.0, 0.0, 0.0, 1.0);
    // (1,0,0) scaled to (2,0,0), rotated 90 deg about +y to (0,0,-2), moved by +x.
    EXPECT_NEAR(p.x(), 1.0, 1e-12);
    EXPECT_NEAR(p.y(), 0.0, 1e-12);
    EXPECT_NEAR(p.z(), -2.0, 1e-12);
}

TEST(SceneJson, BadInputNamesTheField) {
    expectError(edited("\"schema_version\": 1", "\"schema_version\": 2"), "schema_version", "schema 1");
    expectError(edited("\"width\": 64", "\"width\": 0"), "camera.width", "must lie in");
    expectError(edited("\"width\": 64", "\"width\": 64.5"), "camera.width", "whole number");
    expectError(edited("\"look_at\": [0, 0.5, 0]", "\"look_at\": [0, 1, 5]"), "camera.look_at",
                "camera position");
    expectError(edited("\"look_at\": [0, 0.5, 0]", "\"look_at\": [0, 0.5, 0], \"up\": [0, -1, -10]"),
                "camera.up", "parallel");
    expectError(edited("\"radius\": 0.5", "\"radius\": -0.5"), "objects[0].sphere.radius", "must lie in");
    expectError(edited("\"radius\": 0.5", "\"radius\": NaN"), "radius", "not a number JSON allows");
    expectError(edited("\"material\": \"ground\"", "\"material\": \"grund\""), "objects[1].material",
                "no material named 'grund'");
    expectError(edited("\"kind\": \"diffuse\"", "\"kind\": \"velvet\""), "materials[1].kind",
                "unknown material kind");
    expectError(edited("\"albedo\": [0.5, 0.4, 0.3]", "\"albedo\": [0.5, 0.4]"), "albedo", "expected 3");
    expectError(edited("\"albedo\": [0.5, 0.4, 0.3]", "\"albedo\": [0.5, 1.4, 0.3]"), "albedo", "[0, 0.99");
    expectError(edited("{\"name\": \"ground\"", "{\"name\": \"paint\""), "materials[1]", "used twice");
    expectError(edited("\"type\": \"sun\"", "\"type\": \"laser\""), "lights[0].type", "unknown light type");
    expectError(edited("\"direction\": [1, 1, 0]", "\"direction\": [0, 0, 0]"), "direction", "zero");
    expectError(edited("\"plane\": {\"size\": 20}", "\"plane\": {\"size\": 20}, \"sphere\": {}"),
                "objects[1]", "exactly one shape");
    expectError(edited("\"sphere\": {\"radius\": 0.5}", "\"sphere\": {\"radius\": 0.5, \"radus\": 1}"),
                "sphere.radus", "unknown field");
    expectError(edited("\"objects\": [", "\"objcts\": [], \"objects\": ["), "objcts", "unknown field");
    expectError(edited("\"size\": 20}", "\"size\": 20, \"material\": 3}"), "plane.material", "unknown field");
    expectError(R"({"schema_version": 1, "camera": {}, "materials": [], "objects": []})", "objects",
                "no objects");
    expectError(kMinimal.substr(0, kMinimal.size() / 2), "", "truncated");
}

TEST(SceneJson, MissingFilesAreNamed) {
    const test::TempDir dir;
    const std::string mesh_scene =
        edited(R"("sphere": {"radius": 0.5})", R"("mesh": {"file": "missing-teapot.obj"})");
    const auto file = dir.write("scene.json", mesh_scene);
    try {
        (void)loadSceneFile(file);
        FAIL() << "accepted a scene whose mesh file is missing";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("objects[0].mesh.file"), std::string::npos) << what;
        EXPECT_NE(what.find((dir.path() / "missing-teapot.obj").string()), std::string::npos) << what;
    }
    const std::string env_scene =
        edited(R"("lights")", R"("environment": {"file": "nowhere.exr"}, "lights")");
    EXPECT_THROW((void)loadSceneFile(dir.write("env.json", env_scene)), InputError);
    EXPECT_THROW((void)loadSceneFile(dir.path() / "no-such-scene.json"), InputError);
}

TEST(SceneJson, RelativeMeshPathsResolveAgainstTheSceneFolder) {
    const test::TempDir dir;
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const auto file =
        dir.write("scene.json", edited(R"("sphere": {"radius": 0.5})", R"("mesh": {"file": "tri.obj"})"));
    const Scene scene = loadSceneFile(file);
    EXPECT_EQ(std::get<MeshShape>(scene.objects[0].shape).file, dir.path() / "tri.obj");
}

}  // namespace
}  // namespace paintlab::raymaps
