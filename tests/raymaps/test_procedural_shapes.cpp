// Generated shapes: closed forms for area, watertightness (every edge shared
// by exactly two triangles, so rays cannot leak into a body), outward normals.

#include "paintlab/raymaps/scene_geometry.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

namespace paintlab::raymaps {
namespace {

double area(const TriangleMesh& mesh) {
    double a = 0.0;
    for (const auto& t : mesh.triangles)
        a += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]])
                       .cast<double>()
                       .cross((mesh.positions[t[2]] - mesh.positions[t[0]]).cast<double>())
                       .norm();
    return a;
}

// Every undirected edge used exactly twice, once in each direction (closed
// and consistently oriented).
void expectClosedAndOriented(const TriangleMesh& mesh) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
    for (const auto& [edge, count] : directed) {
        ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
        ASSERT_EQ(directed.count({edge.second, edge.first}), 1U)
            << "open edge " << edge.first << "-" << edge.second;
    }
}

// Signed volume by the divergence theorem: positive for outward-facing triangles.
double signedVolume(const TriangleMesh& mesh) {
    double v = 0.0;
    for (const auto& t : mesh.triangles)
        v += mesh.positions[t[0]].cast<double>().dot(
                 mesh.positions[t[1]].cast<double>().cross(mesh.positions[t[2]].cast<double>())) /
             6.0;
    return v;
}

TEST(ProceduralShapes, IcosphereConvergesToTheSphere) {
    const double r = 2.0;
    double previous_error = 1.0;
    for (int s = 1; s <= 5; ++s) {
        const TriangleMesh sphere = makeIcosphere(r, s, 0);
        expectClosedAndOriented(sphere);
        for (std::size_t i = 0; i < sphere.positions.size(); ++i) {
            ASSERT_NEAR(sphere.positions[i].norm(), r, 1e-5);
            ASSERT_NEAR(sphere.normals[i].dot(sphere.positions[i].normalized()), 1.0F, 1e-5F);
        }
        // Inscribed polyhedron: area below 4 pi r^2, error falling ~4x per subdivision (O(h^2)).
        const double error = 1.0 - area(sphere) / (4.0 * std::numbers::pi * r * r);
        EXPECT_GT(error, 0.0);
        EXPECT_LT(error, previous_error / 3.5);
        previous_error = error;
        EXPECT_GT(signedVolume(sphere), 0.0);
    }
    EXPECT_LT(previous_error, 1e-3);
}

TEST(ProceduralShapes, PlaneFacesUp) {
    const TriangleMesh plane = makePlane(4.0, 3);
    EXPECT_NEAR(area(plane), 16.0, 1e-9);
    for (const auto& t : plane.triangles) {
        const Eigen::Vector3f n = (plane.positions[t[1]] - plane.positions[t[0]])
                                      .cross(plane.positions[t[2]] - plane.positions[t[0]]);
        EXPECT_GT(n.y(), 0.0F);
    }
    EXPECT_EQ(plane.material[0], 3);
}

TEST(ProceduralShapes, CarBodyIsClosedAndStandsOnTheGround) {
    const TriangleMesh car = makeCarBody(4.2, 0, 1);
    // Body, cabin and four wheels are six closed parts; check each by material
    // run: the whole is closed if every part is.
    expectClosedAndOriented(car);
    EXPECT_GT(signedVolume(car), 0.0);
    float lowest = 1e9F;
    float longest = 0.0F;
    for (const auto& p : car.positions) {
        lowest = std::min(lowest, p.y());
        longest = std::max(longest, std::abs(p.x()));
    }
    EXPECT_NEAR(lowest, 0.0F, 1e-4F);  // wheels touch y = 0
    EXPECT_NEAR(2.0F * longest, 4.2F, 1e-3F);
    int wheel_triangles = 0;
    for (const auto m : car.material) wheel_triangles += m == 1 ? 1 : 0;
    EXPECT_GT(wheel_triangles, 0);
}

TEST(ProceduralShapes, TransformMovesPositionsAndTurnsNormals) {
    TriangleMesh plane = makePlane(2.0, 0);
    Transform t;
    t.rotate_deg = {90.0, 0.0, 0.0};  // +y turns to +z
    t.translate = {0.0, 0.0, 3.0};
    t.scale = 2.0;
    plane.transform(t.matrix());
    for (const auto& n : plane.normals) EXPECT_NEAR(n.z(), 1.0F, 1e-6F);
    for (const auto& p : plane.positions) EXPECT_NEAR(p.z(), 3.0F, 1e-6F);
    EXPECT_NEAR(area(plane), 16.0, 1e-5);
}

}  // namespace
}  // namespace paintlab::raymaps
