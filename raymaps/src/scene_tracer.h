#pragma once
// The Embree side of the precompute (private: no Embree type leaves src/):
// the scene's triangles as one Embree geometry, closest-hit and shadow
// queries, and the pinhole camera's rays.

#include "sampling.h"

#include "paintlab/raymaps/scene.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <cstdint>
#include <limits>
#include <memory>

namespace paintlab::raymaps {

struct Hit {
    bool found = false;
    double t = 0.0;
    Vec3 position = Vec3::Zero();
    Vec3 geometric_normal = Vec3::UnitY();  // unit, from the triangle's winding
    Vec3 shading_normal = Vec3::UnitY();    // unit, interpolated vertex normals
    int material = -1;
};

class SceneTracer {
public:
    // Throws Error if Embree cannot build the scene.
    explicit SceneTracer(const SceneGeometry& geometry);
    ~SceneTracer();
    SceneTracer(const SceneTracer&) = delete;
    SceneTracer& operator=(const SceneTracer&) = delete;
    SceneTracer(SceneTracer&&) = delete;
    SceneTracer& operator=(SceneTracer&&) = delete;

    // Thread safe. `direction` need not be unit length; t is in its units.
    Hit intersect(const Vec3& origin, const Vec3& direction,
                  double t_max = std::numeric_limits<double>::infinity()) const;
    bool occluded(const Vec3& origin, const Vec3& direction,
                  double t_max = std::numeric_limits<double>::infinity()) const;

    // An offset (scene units) that lifts ray origins off the surface they
    // start on: float positions are exact to ~1e-7 of the scene's size.
    double epsilon() const { return m_epsilon; }
    // Rays traced so far (closest-hit and shadow), over all threads.
    std::uint64_t raysTraced() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    const TriangleMesh& m_mesh;
    double m_epsilon = 1e-4;
};

// A pinhole camera (Camera: position, look_at, up, vertical field of view).
class PinholeCamera {
public:
    explicit PinholeCamera(const Camera& camera);
    // Unit direction through image point (x, y) in pixels, (0, 0) the top-left corner.
    Vec3 direction(double x, double y) const;
    const Vec3& origin() const { return m_origin; }
    // Width of one pixel (scene units) at unit distance along the axis.
    double pixelAngle() const { return m_pixel_angle; }

private:
    Vec3 m_origin, m_forward, m_right, m_up;
    double m_half_height = 1.0;
    double m_pixel_angle = 0.0;
    int m_width = 1;
    int m_height = 1;
};

}  // namespace paintlab::raymaps
