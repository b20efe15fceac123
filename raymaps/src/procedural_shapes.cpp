// Procedural shapes (scene_geometry.h): icosphere, plane, the car-like body.
// Apart from the scene assembly so that a plugin (the glTF exporter) can link
// them without the mesh importer, and so without assimp: an object library
// compiled position-independent (raymaps/CMakeLists.txt).

#include "paintlab/raymaps/scene_geometry.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace paintlab::raymaps {

namespace {

using Vec3f = Eigen::Vector3f;

// Area-weighted vertex normals from the faces (procedural shapes share
// vertices along their seams, so these are smooth).
void normalsFromFaces(TriangleMesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), Vec3f::Zero());
    for (const auto& t : mesh.triangles) {
        const Vec3f n =
            (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
        for (const std::uint32_t v : t) mesh.normals[v] += n;
    }
    for (Vec3f& n : mesh.normals) n = n.norm() > 0.0F ? n.normalized() : Vec3f(0.0F, 1.0F, 0.0F);
}

void addTriangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                 std::uint16_t material) {
    mesh.triangles.push_back({a, b, c});
    mesh.material.push_back(material);
}

double signedPower(double x, double e) { return std::copysign(std::pow(std::abs(x), e), x); }

// A superellipsoid with polar axis y (exponent e_lat along it, e_lon around
// it; 0 -> a box, 1 -> an ellipsoid), centred at `centre`; latitude rings
// plus two pole vertices, so no seam and no degenerate triangle.
TriangleMesh makeSuperellipsoid(const Eigen::Vector3d& half, const Eigen::Vector3d& centre, double e_lat,
                                double e_lon, int rings, int segments, std::uint16_t material) {
    TriangleMesh mesh;
    const auto point = [&](double u, double v) {
        const double cu = std::cos(u);
        const double su = std::sin(u);
        const Eigen::Vector3d p(half.x() * signedPower(cu, e_lat) * signedPower(std::cos(v), e_lon),
                                half.y() * signedPower(su, e_lat),
                                half.z() * signedPower(cu, e_lat) * signedPower(std::sin(v), e_lon));
        return (p + centre).cast<float>().eval();
    };
    const double pi = std::numbers::pi;
    mesh.positions.push_back(point(-pi / 2.0, 0.0));  // bottom pole
    for (int i = 1; i < rings; ++i) {
        const double u = -pi / 2.0 + pi * i / rings;
        for (int j = 0; j < segments; ++j) mesh.positions.push_back(point(u, 2.0 * pi * j / segments));
    }
    mesh.positions.push_back(point(pi / 2.0, 0.0));  // top pole
    const auto ring = [&](int i, int j) {
        return static_cast<std::uint32_t>(1 + (i - 1) * segments + ((j % segments) + segments) % segments);
    };
    const auto top = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    for (int j = 0; j < segments; ++j) {
        // Counter-clockwise seen from outside (v turns from +x towards +z,
        // which seen from above, +y, is clockwise).
        addTriangle(mesh, 0, ring(1, j), ring(1, j + 1), material);
        addTriangle(mesh, top, ring(rings - 1, j + 1), ring(rings - 1, j), material);
        for (int i = 1; i + 1 < rings; ++i) {
            addTriangle(mesh, ring(i, j), ring(i + 1, j + 1), ring(i, j + 1), material);
            addTriangle(mesh, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), material);
        }
    }
    normalsFromFaces(mesh);
    return mesh;
}

// A wheel: a closed, edge-rounded cylinder with its axis along z.
TriangleMesh makeWheel(double radius, double width, const Eigen::Vector3d& centre, int segments,
                       std::uint16_t material) {
    TriangleMesh wheel = makeSuperellipsoid({radius, width / 2.0, radius}, Eigen::Vector3d::Zero(), 0.2, 1.0,
                                            16, segments, material);
    Eigen::Affine3d place = Eigen::Affine3d::Identity();
    place.translate(centre);
    place.rotate(Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitX()));
    wheel.transform(place.matrix());
    return wheel;
}

}  // namespace

void TriangleMesh::append(const TriangleMesh& other) {
    const auto base = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
    for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    material.insert(material.end(), other.material.begin(), other.material.end());
}

void TriangleMesh::transform(const Eigen::Matrix4d& m) {
    const Eigen::Matrix3d linear = m.topLeftCorner<3, 3>();
    const Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    for (Vec3f& p : positions) p = (linear * p.cast<double>() + m.topRightCorner<3, 1>()).cast<float>();
    for (Vec3f& n : normals) n = (normal_matrix * n.cast<double>()).normalized().cast<float>();
}

TriangleMesh makeIcosphere(double radius, int subdivisions, std::uint16_t material) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                      {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                      {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p.normalize();
    std::vector<std::array<std::uint32_t, 3>> f = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        const auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            v.push_back((v[a] + v[b]).normalized());
            const auto index = static_cast<std::uint32_t>(v.size() - 1);
            midpoint.emplace(key, index);
            return index;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        next.reserve(f.size() * 4);
        for (const auto& tri : f) {
            const std::uint32_t a = mid(tri[0], tri[1]);
            const std::uint32_t b = mid(tri[1], tri[2]);
            const std::uint32_t c = mid(tri[2], tri[0]);
            next.push_back({tri[0], a, c});
            next.push_back({tri[1], b, a});
            next.push_back({tri[2], c, b});
            next.push_back({a, b, c});
        }
        f = std::move(next);
    }
    TriangleMesh mesh;
    for (const auto& p : v) {
        mesh.positions.emplace_back((radius * p).cast<float>());
        mesh.normals.emplace_back(p.cast<float>());
    }
    mesh.triangles = std::move(f);
    mesh.material.assign(mesh.triangles.size(), material);
    return mesh;
}

TriangleMesh makePlane(double size, std::uint16_t material) {
    TriangleMesh mesh;
    const auto h = static_cast<float>(size / 2.0);
    mesh.positions = {{-h, 0.0F, -h}, {h, 0.0F, -h}, {h, 0.0F, h}, {-h, 0.0F, h}};
    mesh.normals.assign(4, Vec3f(0.0F, 1.0F, 0.0F));
    addTriangle(mesh, 0, 2, 1, material);  // counter-clockwise seen from +y
    addTriangle(mesh, 0, 3, 2, material);
    return mesh;
}

TriangleMesh makeCarBody(double length, std::uint16_t body_material, std::uint16_t wheel_material) {
    // Proportions of a compact car (length 4.2 m: width 1.8, height 1.45,
    // wheel radius 0.32), scaled with length; +x is forward, lowest point y = 0.
    const double s = length / 4.2;
    const double wheel_r = 0.32 * s;
    TriangleMesh car = makeSuperellipsoid({2.1 * s, 0.36 * s, 0.9 * s}, {0.0, 0.62 * s, 0.0}, 0.25, 0.25, 48,
                                          96, body_material);
    car.append(makeSuperellipsoid({1.15 * s, 0.34 * s, 0.76 * s}, {-0.25 * s, 1.05 * s, 0.0}, 0.45, 0.45, 32,
                                  64, body_material));
    for (const double x : {1.3 * s, -1.3 * s})
        for (const double z : {0.78 * s, -0.78 * s})
            car.append(makeWheel(wheel_r, 0.24 * s, {x, wheel_r, z}, 48, wheel_material));
    return car;
}

}  // namespace paintlab::raymaps
