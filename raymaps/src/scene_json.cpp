#include "json_reader.h"
#include "paintlab/engine/error.h"
#include "paintlab/raymaps/scene.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <set>

namespace paintlab::raymaps {

namespace {

using jsonio::ObjectReader;
using nlohmann::json;

// A scene file is a page of JSON; anything larger is not a scene.
constexpr std::size_t kMaxSceneFileBytes = 16u << 20u;
constexpr int kMaxImageSide = 16384;

Eigen::Vector3d vector3(ObjectReader& reader, std::string_view key, const Eigen::Vector3d& fallback) {
    const json* value = reader.find(key);
    if (value == nullptr) return fallback;
    const std::vector<double> v = reader.fixedNumberArray(key, *value, 3);
    return {v[0], v[1], v[2]};
}

// A colour: three numbers >= 0 (or one, for grey), at most `max` each.
Rgb3 colour(ObjectReader& reader, std::string_view key, const Rgb3& fallback, double max) {
    const json* value = reader.find(key);
    if (value == nullptr) return fallback;
    Rgb3 c;
    if (value->is_number()) {
        c.setConstant(reader.number(key, *value));
    } else {
        const std::vector<double> v = reader.fixedNumberArray(key, *value, 3);
        c = {v[0], v[1], v[2]};
    }
    for (int i = 0; i < 3; ++i)
        if (c[i] < 0.0 || c[i] > max)
            reader.fail(key, "each channel must lie in [0, " + std::to_string(max) + "], found " +
                                 std::to_string(c[i]));
    return c;
}

std::filesystem::path resolveFile(ObjectReader& reader, std::string_view key,
                                  const std::filesystem::path& base) {
    const std::string name = reader.string(key, true);
    if (name.empty()) reader.fail(key, "file name is empty");
    std::filesystem::path path(name);
    if (path.is_relative() && !base.empty()) path = base / path;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) reader.fail(key, "file not found: " + path.string());
    return path;
}

Camera readCamera(const json& value, const std::string& source) {
    ObjectReader r(value, "camera", source);
    Camera c;
    c.position = vector3(r, "position", c.position);
    c.look_at = vector3(r, "look_at", c.look_at);
    c.up = vector3(r, "up", c.up);
    c.vertical_fov_deg = r.numberIn("vertical_fov_deg", 0.0, 170.0, c.vertical_fov_deg, true);
    c.width = r.integerIn("width", 1, kMaxImageSide, c.width);
    c.height = r.integerIn("height", 1, kMaxImageSide, c.height);
    r.finish();
    const Eigen::Vector3d view = c.look_at - c.position;
    if (view.norm() <= 0.0) r.fail("look_at", "equals the camera position");
    if (c.up.norm() <= 0.0 || view.normalized().cross(c.up.normalized()).norm() < 1e-6)
        r.fail("up", "must not be zero or parallel to the viewing direction");
    return c;
}

Environment readEnvironment(const json& value, const std::string& source, const std::filesystem::path& base) {
    ObjectReader r(value, "environment", source);
    Environment e;
    if (r.find("file") != nullptr) e.file = resolveFile(r, "file", base);
    e.rotation_deg = r.numberIn("rotation_deg", -360.0, 360.0, e.rotation_deg);
    e.intensity = r.numberIn("intensity", 0.0, 1e6, e.intensity);
    r.finish();
    return e;
}

Light readLight(const json& value, const std::string& path, const std::string& source) {
    ObjectReader r(value, path, source);
    const std::string type = r.string("type", true);
    if (type == "sun") {
        SunLight sun;
        sun.direction = vector3(r, "direction", sun.direction);
        if (sun.direction.norm() <= 0.0) r.fail("direction", "must not be zero");
        sun.direction.normalize();
        sun.irradiance = colour(r, "irradiance", sun.irradiance, 1e6);
        sun.angular_diameter_deg = r.numberIn("angular_diameter_deg", 0.0, 30.0, sun.angular_diameter_deg);
        r.finish();
        return sun;
    }
    if (type == "point") {
        PointLight point;
        point.position = vector3(r, "position", point.position);
        point.intensity = colour(r, "intensity", point.intensity, 1e9);
        r.finish();
        return point;
    }
    r.fail("type", "unknown light type '" + type + "' (expected sun or point)");
}

MaterialKind materialKind(ObjectReader& r, const std::string& kind) {
    if (kind == "paint") return MaterialKind::Paint;
    if (kind == "diffuse") return MaterialKind::Diffuse;
    if (kind == "glossy") return MaterialKind::Glossy;
    if (kind == "glass") return MaterialKind::Glass;
    if (kind == "mirror") return MaterialKind::Mirror;
    if (kind == "emissive") return MaterialKind::Emissive;
    r.fail("kind", "unknown material kind '" + kind +
                       "' (expected paint, diffuse, glossy, glass, mirror or emissive)");
}

Material readMaterial(const json& value, const std::string& path, const std::string& source) {
    ObjectReader r(value, path, source);
    Material m;
    m.name = r.string("name", true);
    if (m.name.empty()) r.fail("name", "must not be empty");
    m.kind = materialKind(r, r.string("kind", true));
    // Albedo 1 would make a closed scene's path tracing never converge; no real material reaches it.
    m.albedo = colour(r, "albedo", m.albedo, 0.99);
    m.roughness = r.numberIn("roughness", 0.0, 1.0, m.roughness, true);
    m.ior = r.numberIn("ior", 1.0, 4.0, m.ior);
    m.radiance = colour(r, "radiance", m.radiance, 1e9);
    r.finish();
    return m;
}

Transform readTransform(ObjectReader& owner, const std::string& source) {
    Transform t;
    const json* value = owner.find("transform");
    if (value == nullptr) return t;
    ObjectReader r(*value, owner.fieldPath("transform"), source);
    t.translate = vector3(r, "translate", t.translate);
    t.rotate_deg = vector3(r, "rotate_deg", t.rotate_deg);
    t.scale = r.numberIn("scale", 0.0, 1e6, t.scale, true);
    r.finish();
    return t;
}

Shape readShape(ObjectReader& r, const std::string& source, const std::filesystem::path& base) {
    int found = 0;
    Shape shape;
    if (const json* v = r.find("mesh")) {
        ObjectReader m(*v, r.fieldPath("mesh"), source);
        MeshShape mesh;
        mesh.file = resolveFile(m, "file", base);
        mesh.fit_size = m.numberIn("fit_size", 0.0, 1e6, 0.0);
        if (const json* map = m.find("material_map")) {
            if (!map->is_object())
                m.fail("material_map", R"(expected an object {"mesh material": "scene material"})");
            for (const auto& item : map->items()) {
                if (!item.value().is_string())
                    m.fail("material_map", "value for '" + item.key() + "' must be a material name");
                mesh.material_map[item.key()] = item.value().get<std::string>();
            }
        }
        m.finish();
        shape = mesh;
        ++found;
    }
    if (const json* v = r.find("sphere")) {
        ObjectReader s(*v, r.fieldPath("sphere"), source);
        SphereShape sphere;
        sphere.radius = s.numberIn("radius", 0.0, 1e6, sphere.radius, true);
        sphere.subdivisions = s.integerIn("subdivisions", 0, 8, sphere.subdivisions);
        s.finish();
        shape = sphere;
        ++found;
    }
    if (const json* v = r.find("plane")) {
        ObjectReader p(*v, r.fieldPath("plane"), source);
        PlaneShape plane;
        plane.size = p.numberIn("size", 0.0, 1e6, plane.size, true);
        p.finish();
        shape = plane;
        ++found;
    }
    if (const json* v = r.find("car_body")) {
        ObjectReader c(*v, r.fieldPath("car_body"), source);
        CarBodyShape car;
        car.length = c.numberIn("length", 0.0, 1e6, car.length, true);
        car.wheel_material = c.string("wheel_material", false);
        c.finish();
        shape = car;
        ++found;
    }
    if (found != 1) r.fail("", "needs exactly one shape: mesh, sphere, plane or car_body");
    return shape;
}

const json& requireArray(ObjectReader& r, std::string_view key, std::size_t max) {
    const json& value = r.require(key, "an array");
    if (!value.is_array()) r.fail(key, "expected an array, found " + jsonio::typeName(value));
    if (value.size() > max)
        r.fail(key, "has " + std::to_string(value.size()) + " entries; at most " + std::to_string(max));
    return value;
}

}  // namespace

Eigen::Matrix4d Transform::matrix() const {
    constexpr double kDeg = std::numbers::pi / 180.0;
    Eigen::Affine3d a = Eigen::Affine3d::Identity();
    a.translate(translate);
    a.rotate(Eigen::AngleAxisd(rotate_deg.z() * kDeg, Eigen::Vector3d::UnitZ()));
    a.rotate(Eigen::AngleAxisd(rotate_deg.y() * kDeg, Eigen::Vector3d::UnitY()));
    a.rotate(Eigen::AngleAxisd(rotate_deg.x() * kDeg, Eigen::Vector3d::UnitX()));
    a.scale(scale);
    return a.matrix();
}

int Scene::materialIndex(const std::string& name) const {
    for (std::size_t i = 0; i < materials.size(); ++i)
        if (materials[i].name == name) return static_cast<int>(i);
    return -1;
}

Scene parseSceneJson(const std::string& text, const std::filesystem::path& file) {
    const std::string source = file.empty() ? std::string("scene") : file.string();
    const json document = jsonio::parseUntrustedJson(text, source);
    ObjectReader r(document, "", source);
    const double version = r.number("schema_version", "1");
    if (version != 1.0)
        r.fail("schema_version", "this build reads scene schema 1, found " + std::to_string(version));
    const std::filesystem::path base = file.empty() ? std::filesystem::path() : file.parent_path();

    Scene scene;
    scene.file = file;
    scene.camera = readCamera(r.require("camera", "the camera"), source);
    if (const json* env = r.find("environment")) scene.environment = readEnvironment(*env, source, base);

    if (r.find("lights") != nullptr) {
        const json& lights = requireArray(r, "lights", 64);
        for (std::size_t i = 0; i < lights.size(); ++i)
            scene.lights.push_back(readLight(lights[i], r.elementPath("lights", i), source));
    }

    const json& materials = requireArray(r, "materials", 1024);
    std::set<std::string> names;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const std::string path = r.elementPath("materials", i);
        Material m = readMaterial(materials[i], path, source);
        if (!names.insert(m.name).second)
            throw InputError(source, path, "material name '" + m.name + "' is used twice");
        scene.materials.push_back(std::move(m));
    }

    const json& objects = requireArray(r, "objects", 4096);
    if (objects.empty()) r.fail("objects", "the scene has no objects");
    for (std::size_t i = 0; i < objects.size(); ++i) {
        ObjectReader o(objects[i], r.elementPath("objects", i), source);
        SceneObject object;
        object.name = o.string("name", false);
        object.shape = readShape(o, source, base);
        object.material = o.string("material", true);
        if (scene.materialIndex(object.material) < 0)
            o.fail("material", "no material named '" + object.material + "' in materials");
        if (const auto* mesh = std::get_if<MeshShape>(&object.shape))
            for (const auto& [from, to] : mesh->material_map)
                if (scene.materialIndex(to) < 0) {
                    std::string message = "no material named '";
                    message.append(to).append("' (for mesh material '").append(from).append("')");
                    o.fail("mesh.material_map", message);
                }
        if (const auto* car = std::get_if<CarBodyShape>(&object.shape))
            if (!car->wheel_material.empty() && scene.materialIndex(car->wheel_material) < 0)
                o.fail("car_body.wheel_material", "no material named '" + car->wheel_material + "'");
        object.transform = readTransform(o, source);
        o.finish();
        scene.objects.push_back(std::move(object));
    }
    r.finish();
    return scene;
}

Scene loadSceneFile(const std::filesystem::path& path) {
    return parseSceneJson(jsonio::readBoundedTextFile(path, kMaxSceneFileBytes), path);
}

}  // namespace paintlab::raymaps
