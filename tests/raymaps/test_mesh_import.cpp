// Mesh files through assimp: real third-party models load, broken ones give
// an error naming the file or a documented, reported repair.

#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace paintlab::raymaps {
namespace {

const std::filesystem::path kModels = PAINTLAB_ASSIMP_MODELS_DIR;

TriangleMesh import(const std::filesystem::path& file, std::vector<std::string>& repairs) {
    return importMeshFile(file, 0, {}, repairs);
}

void expectUnitNormals(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const auto& n : mesh.normals) ASSERT_NEAR(n.norm(), 1.0F, 1e-5F);
}

TEST(MeshImport, RealModelsInSeveralFormats) {
    // assimp-testmodels (Debian): a box in OBJ, a cube in binary PLY, the Collada duck.
    for (const char* name : {"OBJ/box.obj", "PLY/cube_binary.ply", "Collada/duck.dae"}) {
        SCOPED_TRACE(name);
        std::vector<std::string> repairs;
        const TriangleMesh mesh = import(kModels / name, repairs);
        EXPECT_GT(mesh.triangleCount(), 10U);
        EXPECT_EQ(mesh.material.size(), mesh.triangleCount());
        expectUnitNormals(mesh);
        for (const auto& t : mesh.triangles)
            for (const auto v : t) ASSERT_LT(v, mesh.positions.size());
    }
}

TEST(MeshImport, MissingNormalsAreComputedAndReported) {
    const test::TempDir dir;
    // A unit square as two triangles, no normals in the file: the computed ones face +z.
    const auto file = dir.write("square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    std::vector<std::string> repairs;
    const TriangleMesh mesh = import(file, repairs);
    ASSERT_EQ(mesh.triangleCount(), 2U);
    for (const auto& n : mesh.normals) EXPECT_NEAR(n.z(), 1.0F, 1e-6F);
    ASSERT_EQ(repairs.size(), 1U);
    EXPECT_NE(repairs[0].find("normals"), std::string::npos);
    EXPECT_NE(repairs[0].find(file.string()), std::string::npos);
}

TEST(MeshImport, ZeroAreaTrianglesAreDroppedAndReported) {
    const test::TempDir dir;
    // Second face repeats a vertex, third is collinear: both have zero area.
    const auto file =
        dir.write("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 1 3\nf 1 2 4\n");
    std::vector<std::string> repairs;
    const TriangleMesh mesh = import(file, repairs);
    EXPECT_EQ(mesh.triangleCount(), 1U);
    bool reported = false;
    for (const auto& r : repairs) reported = reported || r.find("dropped 2 zero-area") != std::string::npos;
    EXPECT_TRUE(reported);
}

TEST(MeshImport, BrokenFilesAreErrorsNamingTheFile) {
    const test::TempDir dir;
    const auto expectError = [](const std::filesystem::path& file, const std::string& part) {
        std::vector<std::string> repairs;
        try {
            (void)importMeshFile(file, 0, {}, repairs);
            FAIL() << "accepted " << file;
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(file.string()), std::string::npos) << what;
            EXPECT_NE(what.find(part), std::string::npos) << what;
        }
    };
    expectError(dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), "vertex 1");
    expectError(dir.write("inf.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                          "end_header\n0 0 0\n1 0 0\n0 1e39 0\n3 0 1 2\n"),
                "not a finite number");
    expectError(dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), "no triangles");
    expectError(dir.write("garbage.obj", std::string(4096, '\x07')), "");
    expectError(dir.write("empty.obj", ""), "");
    expectError(dir.path() / "absent.obj", "");
}

}  // namespace
}  // namespace paintlab::raymaps

namespace paintlab::raymaps {
namespace {

TEST(SceneGeometry, FitsMeshesAndAssignsMaterials) {
    Scene scene;
    scene.materials = {{"paint", MaterialKind::Paint}, {"ground", MaterialKind::Diffuse}};
    MeshShape duck;
    duck.file = kModels / "Collada/duck.dae";
    duck.fit_size = 2.0;
    scene.objects.push_back({"duck", duck, "paint", {}});
    SceneObject floor{"floor", PlaneShape{10.0}, "ground", {}};
    floor.transform.translate = {0.0, -0.5, 0.0};
    scene.objects.push_back(floor);
    const SceneGeometry geometry = buildSceneGeometry(scene);
    // The duck is scaled to a largest side of 2 with its lowest point on y = 0;
    // the floor below it sets the bounds' bottom and sides.
    EXPECT_NEAR(geometry.bounds_min.y(), -0.5F, 1e-6F);
    EXPECT_NEAR(geometry.bounds_max.x(), 5.0F, 1e-6F);
    float duck_low = 1e9F;
    float duck_high = -1e9F;
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9F);
    Eigen::Vector3f hi = -lo;
    std::size_t paint = 0;
    for (std::size_t t = 0; t < geometry.mesh.triangleCount(); ++t) {
        if (geometry.mesh.material[t] != 0) continue;
        ++paint;
        for (const auto v : geometry.mesh.triangles[t]) {
            lo = lo.cwiseMin(geometry.mesh.positions[v]);
            hi = hi.cwiseMax(geometry.mesh.positions[v]);
            duck_low = std::min(duck_low, geometry.mesh.positions[v].y());
            duck_high = std::max(duck_high, geometry.mesh.positions[v].y());
        }
    }
    EXPECT_EQ(paint + 2, geometry.mesh.triangleCount());  // the plane is 2 triangles
    EXPECT_NEAR((hi - lo).maxCoeff(), 2.0F, 1e-4F);
    EXPECT_NEAR(duck_low, 0.0F, 1e-4F);
    EXPECT_GT(duck_high, 0.5F);
}

}  // namespace
}  // namespace paintlab::raymaps
