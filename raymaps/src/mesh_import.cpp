// Mesh files through assimp, checked and repaired as scene_geometry.h says.

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>

#include <cmath>

namespace paintlab::raymaps {

namespace {

// Larger meshes would not fit the ray map's per-scene budget anyway; refusing
// them early keeps a malicious file from exhausting memory.
constexpr std::size_t kMaxTriangles = 20'000'000;

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

TriangleMesh importMeshFile(const std::filesystem::path& file, std::uint16_t material,
                            const std::vector<std::pair<std::string, std::uint16_t>>& material_map,
                            std::vector<std::string>& repairs) {
    const std::string name = file.string();
    Assimp::Importer importer;
    // Points and lines are not surfaces; SortByPType with this setting drops them.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // Normals are checked and, where needed, recomputed here rather than by
    // assimp, so that every repair is known and reported.
    const aiScene* scene = importer.ReadFile(name, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                       aiProcess_SortByPType);
    if (scene == nullptr)
        throw InputError(name, "", std::string("cannot read mesh: ") + importer.GetErrorString());
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0U)
        throw InputError(name, "", "mesh file is incomplete");

    TriangleMesh out;
    std::size_t dropped = 0;
    std::size_t renormalised = 0;
    for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
        const aiMesh* mesh = scene->mMeshes[mi];
        if ((mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0U) continue;
        std::uint16_t mesh_material = material;
        if (mesh->mMaterialIndex < scene->mNumMaterials) {
            const std::string mat_name = scene->mMaterials[mesh->mMaterialIndex]->GetName().C_Str();
            for (const auto& [from, to] : material_map)
                if (from == mat_name) mesh_material = to;
        }
        const std::string mesh_label = "mesh " + std::to_string(mi) + " '" + mesh->mName.C_Str() + "'";
        const auto base = static_cast<std::uint32_t>(out.positions.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            if (!finite(p))
                throw InputError(name, mesh_label + " > vertex " + std::to_string(v),
                                 "position is not a finite number (NaN or infinity)");
            out.positions.emplace_back(p.x, p.y, p.z);
            Eigen::Vector3f n = Eigen::Vector3f::Zero();
            if (mesh->mNormals != nullptr && finite(mesh->mNormals[v]))
                n = {mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z};
            out.normals.push_back(n);  // zero = recompute below
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            std::array<std::uint32_t, 3> t{};
            bool valid = true;
            for (int k = 0; k < 3; ++k) {
                if (face.mIndices[k] >= mesh->mNumVertices) valid = false;
                t[static_cast<std::size_t>(k)] = base + face.mIndices[k];
            }
            if (!valid)
                throw InputError(name, mesh_label + " > face " + std::to_string(f),
                                 "vertex index out of range");
            const Eigen::Vector3f e1 = out.positions[t[1]] - out.positions[t[0]];
            const Eigen::Vector3f e2 = out.positions[t[2]] - out.positions[t[0]];
            const float scale = std::max(e1.squaredNorm(), e2.squaredNorm());
            // Zero area relative to the triangle's own size (float round-off ~1e-7).
            if (!(e1.cross(e2).squaredNorm() > 1e-12F * scale * scale)) {
                ++dropped;
                continue;
            }
            out.triangles.push_back(t);
            out.material.push_back(mesh_material);
            if (out.triangles.size() > kMaxTriangles)
                throw InputError(name, "", "more than " + std::to_string(kMaxTriangles) + " triangles");
        }
    }
    if (out.triangles.empty()) throw InputError(name, "", "the mesh has no triangles with non-zero area");

    // Vertex normals that are missing, zero or not unit: area-weighted face normals.
    std::vector<Eigen::Vector3f> face_sum(out.positions.size(), Eigen::Vector3f::Zero());
    for (const auto& t : out.triangles) {
        const Eigen::Vector3f n =
            (out.positions[t[1]] - out.positions[t[0]]).cross(out.positions[t[2]] - out.positions[t[0]]);
        for (const std::uint32_t v : t) face_sum[v] += n;
    }
    for (std::size_t v = 0; v < out.normals.size(); ++v) {
        Eigen::Vector3f& n = out.normals[v];
        if (std::abs(n.norm() - 1.0F) < 1e-3F) continue;
        if (n.norm() > 0.0F && std::isfinite(n.norm())) {
            n.normalize();
            continue;
        }
        ++renormalised;
        n = face_sum[v].norm() > 0.0F ? face_sum[v].normalized() : Eigen::Vector3f(0.0F, 1.0F, 0.0F);
    }
    if (dropped > 0)
        repairs.push_back(name + ": dropped " + std::to_string(dropped) + " zero-area triangles");
    if (renormalised > 0)
        repairs.push_back(name + ": computed " + std::to_string(renormalised) +
                          " missing or invalid vertex normals from the faces");
    return out;
}

}  // namespace paintlab::raymaps
