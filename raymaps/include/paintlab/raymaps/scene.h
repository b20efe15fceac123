#pragma once
// A scene file (shared/ARCHITECTURE.md, "Ray maps"): which meshes, which of
// their materials is *the paint*, what the other materials are, the camera,
// the HDR environment and optional sun / point lights. Read from JSON by
// loadSceneFile; docs/SCENE_FORMAT.md describes the format.
//
// Units and conventions: right-handed world, +y up (as glTF); lengths in
// scene units (the paint's microstructure does not depend on them); colours
// are linear Rec.709 / sRGB primaries; radiance in W / (m^2 sr) per channel,
// sun irradiance in W / m^2 per channel on a surface facing it, point-light
// intensity in W / sr per channel.

#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace paintlab::raymaps {

using Rgb3 = Eigen::Vector3d;

enum class MaterialKind {
    Paint,     // shaded by the recipe's LayeredBrdf at relight time
    Diffuse,   // Lambertian, albedo
    Glossy,    // Lambertian base under a rough dielectric coat (roughness = GGX alpha)
    Glass,     // smooth clear dielectric (ior), both sides
    Mirror,    // smooth conductor with a reflectance colour
    Emissive,  // a black body that emits `radiance`
};

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Diffuse;
    Rgb3 albedo{0.5, 0.5, 0.5};    // Diffuse, Glossy base; Mirror reflectance
    double roughness = 0.1;        // Glossy: GGX alpha of the coat
    double ior = 1.5;              // Glass, Glossy coat
    Rgb3 radiance{0.0, 0.0, 0.0};  // Emissive
};

struct Camera {
    Eigen::Vector3d position{0.0, 1.0, 5.0};
    Eigen::Vector3d look_at{0.0, 0.5, 0.0};
    Eigen::Vector3d up{0.0, 1.0, 0.0};
    double vertical_fov_deg = 40.0;
    int width = 640;
    int height = 360;
};

struct Environment {
    // Lat-long HDR image (OpenEXR, Radiance .hdr, anything OpenImageIO reads);
    // empty: the built-in analytic sky (builtin_sky.h).
    std::filesystem::path file;
    double rotation_deg = 0.0;  // about +y
    double intensity = 1.0;     // multiplies the radiance
};

struct SunLight {
    Eigen::Vector3d direction{0.0, 1.0, 0.0};  // towards the sun, normalised on load
    Rgb3 irradiance{1.0, 1.0, 1.0};            // W/m^2 per channel, normal to the beam
    double angular_diameter_deg = 0.53;
};

struct PointLight {
    Eigen::Vector3d position{0.0, 3.0, 0.0};
    Rgb3 intensity{1.0, 1.0, 1.0};  // W/sr per channel
};

using Light = std::variant<SunLight, PointLight>;

// Scale, then rotate (degrees about x, then y, then z), then translate.
struct Transform {
    Eigen::Vector3d translate{0.0, 0.0, 0.0};
    Eigen::Vector3d rotate_deg{0.0, 0.0, 0.0};
    double scale = 1.0;
    Eigen::Matrix4d matrix() const;
};

struct MeshShape {
    std::filesystem::path file;  // resolved against the scene file's folder
    // The mesh file's material names -> scene material names; a mesh
    // material not listed here takes the object's `material`.
    std::map<std::string, std::string> material_map;
    // Scale the mesh so its bounding box's largest side is this (0: as is),
    // centred on the origin with its lowest point at y = 0 (before transform).
    double fit_size = 0.0;
};
struct SphereShape {
    double radius = 1.0;
    int subdivisions = 5;  // icosphere
};
struct PlaneShape {
    double size = 10.0;  // square in the xz plane, normal +y
};
// A generic car-like body (rounded box hood, cabin, wheels): a recognisable
// paint carrier that needs no mesh file.
struct CarBodyShape {
    double length = 4.2;
    std::string wheel_material;  // empty: the object's material
};

using Shape = std::variant<MeshShape, SphereShape, PlaneShape, CarBodyShape>;

struct SceneObject {
    std::string name;
    Shape shape;
    std::string material;  // a name in Scene::materials
    Transform transform;
};

struct Scene {
    std::filesystem::path file;  // where it was read from (for messages); may be empty
    Camera camera;
    Environment environment;
    std::vector<Light> lights;
    std::vector<Material> materials;
    std::vector<SceneObject> objects;

    // Index into materials, or -1.
    int materialIndex(const std::string& name) const;
};

// Reads and checks a scene file. Throws InputError naming the file and the
// field (unknown keys, missing fields, NaN, non-positive sizes, unknown
// material names, a missing mesh or environment file).
Scene loadSceneFile(const std::filesystem::path& path);
Scene parseSceneJson(const std::string& text, const std::filesystem::path& file);

}  // namespace paintlab::raymaps
