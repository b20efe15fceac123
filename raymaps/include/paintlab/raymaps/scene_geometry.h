#pragma once
// A scene's triangles in world space, one flat mesh for the ray tracer, with
// a material per triangle. Meshes come through assimp (OBJ, PLY, glTF 2,
// Collada, ...) or are generated (sphere, plane, car-like body).
//
// Broken meshes: a vertex that is NaN or infinite, a mesh with no triangles
// or a file assimp cannot read is an InputError naming the file (and the
// vertex). Documented repairs, each reported in SceneGeometry::repairs:
// missing or invalid vertex normals are recomputed from the faces (area
// weighted); zero-area triangles are dropped; points and lines are ignored.

#include "paintlab/raymaps/scene.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace paintlab::raymaps {

struct TriangleMesh {
    std::vector<Eigen::Vector3f> positions;
    std::vector<Eigen::Vector3f> normals;  // per vertex, unit length
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint16_t> material;  // per triangle: index into Scene::materials

    std::size_t triangleCount() const { return triangles.size(); }
    // Appends other (indices shifted).
    void append(const TriangleMesh& other);
    // Applies an affine transform to positions (and its inverse transpose to normals).
    void transform(const Eigen::Matrix4d& m);
};

struct SceneGeometry {
    TriangleMesh mesh;
    std::vector<std::string> repairs;  // what was repaired, one line each, naming the file
    Eigen::Vector3f bounds_min{0.0F, 0.0F, 0.0F};
    Eigen::Vector3f bounds_max{0.0F, 0.0F, 0.0F};
};

// Loads one mesh file; every triangle gets `material` unless the file's own
// material name is in `material_map` (scene material indices).
TriangleMesh importMeshFile(const std::filesystem::path& file, std::uint16_t material,
                            const std::vector<std::pair<std::string, std::uint16_t>>& material_map,
                            std::vector<std::string>& repairs);

TriangleMesh makeIcosphere(double radius, int subdivisions, std::uint16_t material);
TriangleMesh makePlane(double size, std::uint16_t material);
TriangleMesh makeCarBody(double length, std::uint16_t body_material, std::uint16_t wheel_material);

// All objects of the scene, transformed, in one mesh.
SceneGeometry buildSceneGeometry(const Scene& scene);

}  // namespace paintlab::raymaps
