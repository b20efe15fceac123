#include "scene_tracer.h"

#include "paintlab/engine/error.h"

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>

#include <cmath>
#include <string>

namespace paintlab::raymaps {

namespace {

void onEmbreeError(void* user, RTCError /*code*/, const char* message) {
    auto* text = static_cast<std::string*>(user);
    if (text->empty()) *text = message != nullptr ? message : "unknown Embree error";
}

RTCRay makeRay(const Vec3& origin, const Vec3& direction, double t_max) {
    RTCRay ray{};
    ray.org_x = static_cast<float>(origin.x());
    ray.org_y = static_cast<float>(origin.y());
    ray.org_z = static_cast<float>(origin.z());
    ray.dir_x = static_cast<float>(direction.x());
    ray.dir_y = static_cast<float>(direction.y());
    ray.dir_z = static_cast<float>(direction.z());
    ray.tnear = 0.0F;
    ray.tfar = std::isfinite(t_max) ? static_cast<float>(t_max) : std::numeric_limits<float>::infinity();
    ray.mask = 0xFFFFFFFFU;
    ray.flags = 0;
    return ray;
}

}  // namespace

struct SceneTracer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;
    // Per thread, so counting costs no shared cache line.
    tbb::enumerable_thread_specific<std::uint64_t> rays{0};
    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    Impl(Impl&&) = delete;
    Impl& operator=(Impl&&) = delete;
    ~Impl() {
        if (scene != nullptr) rtcReleaseScene(scene);
        if (device != nullptr) rtcReleaseDevice(device);
    }
    void check(const char* what) const {
        if (!error.empty()) throw Error(std::string("Embree (") + what + "): " + error);
    }
};

SceneTracer::SceneTracer(const SceneGeometry& geometry)
    : m_impl(std::make_unique<Impl>()), m_mesh(geometry.mesh) {
    m_impl->device = rtcNewDevice(nullptr);
    if (m_impl->device == nullptr) throw Error("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(m_impl->device, onEmbreeError, &m_impl->error);
    m_impl->scene = rtcNewScene(m_impl->device);
    // Robust traversal: no ray slips between two triangles sharing an edge.
    rtcSetSceneFlags(m_impl->scene, RTC_SCENE_FLAG_ROBUST);
    m_impl->check("scene");
    const TriangleMesh& mesh = geometry.mesh;
    RTCGeometry geom = rtcNewGeometry(m_impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.positions.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    m_impl->check("buffers");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k) vb[3 * i + k] = mesh.positions[i][static_cast<Eigen::Index>(k)];
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k) ib[3 * i + k] = mesh.triangles[i][k];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m_impl->scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(m_impl->scene);
    m_impl->check("commit");
    const double size = (geometry.bounds_max - geometry.bounds_min).cast<double>().norm();
    m_epsilon = std::max(1e-6, 2e-5 * size);
}

SceneTracer::~SceneTracer() = default;

Hit SceneTracer::intersect(const Vec3& origin, const Vec3& direction, double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray = makeRay(origin, direction, t_max);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_impl->scene, &context, &rh);
    ++m_impl->rays.local();
    Hit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    const auto& tri = m_mesh.triangles[rh.hit.primID];
    const Eigen::Vector3f& p0 = m_mesh.positions[tri[0]];
    const Eigen::Vector3f& p1 = m_mesh.positions[tri[1]];
    const Eigen::Vector3f& p2 = m_mesh.positions[tri[2]];
    Vec3 ng = (p1 - p0).cross(p2 - p0).cast<double>();
    const double len = ng.norm();
    if (!(len > 0.0)) return hit;
    hit.found = true;
    hit.t = static_cast<double>(rh.ray.tfar);
    const auto u = static_cast<double>(rh.hit.u);
    const auto v = static_cast<double>(rh.hit.v);
    // Interpolating the triangle's own vertices is more precise than origin + t dir.
    hit.position = (1.0 - u - v) * p0.cast<double>() + u * p1.cast<double>() + v * p2.cast<double>();
    hit.geometric_normal = ng / len;
    const Vec3 ns = (1.0 - u - v) * m_mesh.normals[tri[0]].cast<double>() +
                    u * m_mesh.normals[tri[1]].cast<double>() + v * m_mesh.normals[tri[2]].cast<double>();
    const double ns_len = ns.norm();
    hit.shading_normal = ns_len > 0.0 ? Vec3(ns / ns_len) : hit.geometric_normal;
    hit.material = m_mesh.material[rh.hit.primID];
    return hit;
}

bool SceneTracer::occluded(const Vec3& origin, const Vec3& direction, double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(origin, direction, t_max);
    rtcOccluded1(m_impl->scene, &context, &ray);
    ++m_impl->rays.local();
    // Embree marks an occluded ray by setting tfar to -inf.
    return ray.tfar < 0.0F;
}

std::uint64_t SceneTracer::raysTraced() const {
    std::uint64_t total = 0;
    for (const std::uint64_t n : m_impl->rays) total += n;
    return total;
}

PinholeCamera::PinholeCamera(const Camera& camera)
    : m_origin(camera.position), m_width(camera.width), m_height(camera.height) {
    m_forward = (camera.look_at - camera.position).normalized();
    m_right = m_forward.cross(camera.up).normalized();
    m_up = m_right.cross(m_forward);
    m_half_height = std::tan(0.5 * camera.vertical_fov_deg * kPi / 180.0);
    m_pixel_angle = 2.0 * m_half_height / camera.height;
}

Vec3 PinholeCamera::direction(double x, double y) const {
    const double sx = (2.0 * x - m_width) / m_height * m_half_height;
    const double sy = (m_height - 2.0 * y) / m_height * m_half_height;
    return (m_forward + sx * m_right + sy * m_up).normalized();
}

}  // namespace paintlab::raymaps
