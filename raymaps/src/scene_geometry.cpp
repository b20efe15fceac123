// The assembly of a scene's objects into one mesh (the shapes: procedural_shapes.cpp).

#include "paintlab/raymaps/scene_geometry.h"

#include "paintlab/engine/error.h"

#include <Eigen/Geometry>

#include <utility>

namespace paintlab::raymaps {

namespace {
using Vec3f = Eigen::Vector3f;
}  // namespace

SceneGeometry buildSceneGeometry(const Scene& scene) {
    SceneGeometry out;
    for (const SceneObject& object : scene.objects) {
        const auto material = static_cast<std::uint16_t>(scene.materialIndex(object.material));
        TriangleMesh mesh;
        if (const auto* m = std::get_if<MeshShape>(&object.shape)) {
            std::vector<std::pair<std::string, std::uint16_t>> map;
            for (const auto& [from, to] : m->material_map)
                map.emplace_back(from, static_cast<std::uint16_t>(scene.materialIndex(to)));
            mesh = importMeshFile(m->file, material, map, out.repairs);
            if (m->fit_size > 0.0) {
                Vec3f lo = mesh.positions.front();
                Vec3f hi = lo;
                for (const Vec3f& p : mesh.positions) {
                    lo = lo.cwiseMin(p);
                    hi = hi.cwiseMax(p);
                }
                const Eigen::Vector3d lo_d = lo.cast<double>();
                const Eigen::Vector3d hi_d = hi.cast<double>();
                const double extent = (hi_d - lo_d).maxCoeff();
                Eigen::Affine3d fit = Eigen::Affine3d::Identity();
                fit.scale(extent > 0.0 ? m->fit_size / extent : 1.0);
                fit.translate(
                    -Eigen::Vector3d(0.5 * (lo_d.x() + hi_d.x()), lo_d.y(), 0.5 * (lo_d.z() + hi_d.z())));
                mesh.transform(fit.matrix());
            }
        } else if (const auto* sphere = std::get_if<SphereShape>(&object.shape)) {
            mesh = makeIcosphere(sphere->radius, sphere->subdivisions, material);
        } else if (const auto* plane = std::get_if<PlaneShape>(&object.shape)) {
            mesh = makePlane(plane->size, material);
        } else if (const auto* car = std::get_if<CarBodyShape>(&object.shape)) {
            const int wheels = car->wheel_material.empty() ? static_cast<int>(material)
                                                           : scene.materialIndex(car->wheel_material);
            mesh = makeCarBody(car->length, material, static_cast<std::uint16_t>(wheels));
        }
        mesh.transform(object.transform.matrix());
        out.mesh.append(mesh);
    }
    if (out.mesh.positions.empty())
        throw InputError(scene.file.string(), "objects", "the scene has no triangles");
    out.bounds_min = out.bounds_max = out.mesh.positions.front();
    for (const Vec3f& p : out.mesh.positions) {
        out.bounds_min = out.bounds_min.cwiseMin(p);
        out.bounds_max = out.bounds_max.cwiseMax(p);
    }
    return out;
}

}  // namespace paintlab::raymaps
