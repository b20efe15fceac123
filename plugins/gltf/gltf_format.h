#pragma once
// glTF 2.0 files of a painted object (issue 29): the glTF plugin's format.
//
// One scene, one node, one mesh: the object (kExportObjects, plugin.h) as
// raymaps makes it for the demo scenes (raymaps/scene_geometry.h: an
// icosphere of radius 0.5 m, a 0.3 m square panel facing +y, the car body
// of 4.2 m with its wheels), +y up, metres. One primitive per material:
// the paint (the fitted glTF material, approx/material_fit.h) and, for the
// car, the tyres (the demo scenes' "tyre": base colour 0.03, roughness
// 0.35). Attributes POSITION (with min and max) and NORMAL (unit length),
// indices unsigned int, one buffer: embedded as a base64 data URI in a
// .gltf, the binary chunk of a .glb.
//
// The paint material uses KHR_materials_ior, KHR_materials_specular,
// KHR_materials_clearcoat and, when fitted, KHR_materials_iridescence; its
// `extras.paintlab` holds the recipe, the fit's directions and residual, and
// the ΔE00 left at the six multi-angle geometries, so the file carries how
// far the approximation is from the paint.

#include "paintlab/engine/approx/material_fit.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <string>
#include <string_view>

namespace paintlab::plugins::gltf {

// The object's mesh: material 0 is the paint, 1 the tyres. Throws InputError
// (field "object") for a name not in kExportObjects.
raymaps::TriangleMesh objectMesh(std::string_view object);

struct Provenance {
    std::string recipe_name;
    std::string recipe_path;
    std::string settings_json;  // the fast model's settings ("{}" if none)
    std::string object;
};

struct GltfAsset {
    std::string json;    // the document (compact), its buffer without a uri
    std::string buffer;  // positions, normals, indices of every primitive
};

GltfAsset makeAsset(const raymaps::TriangleMesh& mesh, const approx::MaterialFit& fit,
                    const Provenance& provenance);
// The .gltf text: the buffer embedded as a base64 data URI.
std::string gltfText(const GltfAsset& asset);
// The .glb bytes: header, JSON chunk, BIN chunk (glTF 2.0 section 4.4).
std::string glbBytes(const GltfAsset& asset);

// RFC 4648 base64 with padding.
std::string base64(std::string_view bytes);

}  // namespace paintlab::plugins::gltf
