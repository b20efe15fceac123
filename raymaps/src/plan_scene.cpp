// A scene or ray map summarised for the effect planner (plan_scene.h).

#include "paintlab/raymaps/plan_scene.h"

#include "record_layout.h"
#include "sampling.h"
#include "scene_tracer.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

namespace paintlab::raymaps {

namespace {

// The ray map's defaults (RayMapSettings): the same hotspots become lights.
constexpr int kEnvLights = 4;
constexpr double kEnvThreshold = 50.0;

// The scene unit in metres: the options', else `fallback`.
double checkOptions(const PlanSceneOptions& o, double fallback) {
    const double unit = o.scene_unit_m.value_or(fallback);
    if (!(unit > 0.0) || !std::isfinite(unit))
        throw InputError("<argument>", "scene_unit_m", std::to_string(unit) + " must be > 0");
    return unit;
}

void summariseEnvironment(const EnvironmentMap& residual, PlanScene& s) {
    constexpr int kW = 128;
    constexpr int kH = 64;
    std::vector<double> lum(static_cast<std::size_t>(kW) * static_cast<std::size_t>(kH));
    const auto at = [&](int v, int u) -> double& {
        return lum[static_cast<std::size_t>(v) * static_cast<std::size_t>(kW) + static_cast<std::size_t>(u)];
    };
    double sum = 0.0;
    double weight = 0.0;
    double peak = 0.0;
    for (int v = 0; v < kH; ++v) {
        const double theta = kPi * (v + 0.5) / kH;
        for (int u = 0; u < kW; ++u) {
            const double phi = 2.0 * kPi * (u + 0.5) / kW;
            const Vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            const double l = luminance(residual.radiance(d));
            at(v, u) = l;
            sum += l * std::sin(theta);
            weight += std::sin(theta);
            peak = std::max(peak, l);
        }
    }
    const double mean = weight > 0.0 ? sum / weight : 0.0;
    s.environment_radiance = mean;
    double gradient = 0.0;  // per radian of arc
    const double dtheta = kPi / kH;
    for (int v = 0; v < kH; ++v) {
        const double theta = kPi * (v + 0.5) / kH;
        const double dphi_arc = 2.0 * kPi / kW * std::max(std::sin(theta), 0.05);
        for (int u = 0; u < kW; ++u) {
            const double l = at(v, u);
            const double right = at(v, (u + 1) % kW);
            gradient = std::max(gradient, std::abs(right - l) / dphi_arc);
            if (v + 1 < kH) gradient = std::max(gradient, std::abs(at(v + 1, u) - l) / dtheta);
        }
    }
    const double width_deg = gradient > 0.0 ? (peak - mean) / gradient * 180.0 / kPi : 180.0;
    s.environment_sharpness_deg = std::clamp(width_deg, 180.0 / kH, 180.0);
}

}  // namespace

PlanScene summariseScene(const Scene& scene, const PlanSceneOptions& options) {
    const double unit_m = checkOptions(options, 1.0);
    PlanScene s;
    s.source = scene.file.empty() ? "<scene>" : scene.file.string();

    // Footprints: distances along a 32 x 18 grid of camera rays to the paint
    // they meet first (paint seen in mirrors or through glass is not followed).
    const SceneGeometry geometry = buildSceneGeometry(scene);
    const SceneTracer tracer(geometry);
    const PinholeCamera camera(scene.camera);
    double near = 1e300;
    double far = 0.0;
    Vec3 centre = Vec3::Zero();
    double paint_hits = 0.0;
    constexpr int kRaysX = 32;
    constexpr int kRaysY = 18;
    for (int y = 0; y < kRaysY; ++y)
        for (int x = 0; x < kRaysX; ++x) {
            const Vec3 dir = camera.direction((x + 0.5) * scene.camera.width / kRaysX,
                                              (y + 0.5) * scene.camera.height / kRaysY);
            const Hit hit = tracer.intersect(camera.origin(), dir);
            if (!hit.found || hit.material < 0 ||
                static_cast<std::size_t>(hit.material) >= scene.materials.size() ||
                scene.materials[static_cast<std::size_t>(hit.material)].kind != MaterialKind::Paint)
                continue;
            near = std::min(near, hit.t);
            far = std::max(far, hit.t);
            centre += hit.position;
            paint_hits += 1.0;
        }
    if (paint_hits > 0.0) {
        centre /= paint_hits;
        const double angle = camera.pixelAngle();
        s.footprint_min_um = near * angle * unit_m * 1e6;
        s.footprint_max_um = far * angle * unit_m * 1e6;
        s.viewing_distance_m = near * unit_m;
    }

    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const std::string name = "light " + std::to_string(i + 1);
        if (const auto* sun = std::get_if<SunLight>(&scene.lights[i])) {
            const double r = 0.5 * sun->angular_diameter_deg * kPi / 180.0;
            s.lights.push_back(
                {name + " (sun)", luminance(sun->irradiance), 2.0 * kPi * (1.0 - std::cos(r))});
        } else if (const auto* point = std::get_if<PointLight>(&scene.lights[i])) {
            const double r2 = std::max((point->position - centre).squaredNorm(), 1e-12);
            s.lights.push_back({name + " (point)", luminance(point->intensity) / r2, 0.0});
        }
    }
    const EnvironmentMap env = EnvironmentMap::load(scene.environment);
    std::vector<EnvironmentMap::Hotspot> hotspots;
    const EnvironmentMap residual = env.withoutHotspots(kEnvLights, kEnvThreshold, hotspots);
    for (std::size_t i = 0; i < hotspots.size(); ++i)
        s.lights.push_back({"environment hotspot " + std::to_string(i + 1), luminance(hotspots[i].irradiance),
                            hotspots[i].solid_angle_sr});
    summariseEnvironment(residual, s);
    return s;
}

PlanScene summariseRayMap(const RayMap& map, const PlanSceneOptions& options) {
    const RayMapHeader& h = map.header();
    const double unit_m = checkOptions(options, h.scene_unit_m);
    PlanScene s;
    s.source = map.path().string();
    for (std::size_t i = 0; i < h.lights.size(); ++i) {
        const ExplicitLight& l = h.lights[i];
        const bool env = static_cast<int>(i) >= static_cast<int>(h.lights.size()) - h.env_lights;
        s.lights.push_back({(env ? "environment hotspot " : "light ") + std::to_string(i + 1),
                            luminance(l.power), l.solid_angle_sr});
    }
    const RecordLayout layout{h.cells, h.orders, static_cast<int>(h.lights.size())};
    std::vector<double> footprints;
    double moment_sum = 0.0;
    for (int b = 0; b < map.bandCount(); ++b) {
        const RayMapBand& band = map.band(b);
        for (std::size_t r = 0; r < band.record_count; ++r) {
            const std::byte* rec = band.records.data() + r * layout.bytes();
            footprints.push_back(static_cast<double>(recordHalf(rec + RecordLayout::kFootprint)));
            // l^0_j summed over the cells is the irradiance of the rest of the
            // light (pi L for a uniform radiance L).
            Rgb3 e = Rgb3::Zero();
            for (int j = 0; j < h.cells; ++j)
                for (int c = 0; c < 3; ++c)
                    e[c] += static_cast<double>(recordHalf(rec + RecordLayout::kMoments0 +
                                                           6 * static_cast<std::size_t>(j) +
                                                           2 * static_cast<std::size_t>(c)));
            moment_sum += luminance(e) / kPi;
        }
    }
    if (!footprints.empty()) {
        std::sort(footprints.begin(), footprints.end());
        const auto at = [&](double q) {
            return footprints[static_cast<std::size_t>(q * static_cast<double>(footprints.size() - 1))];
        };
        s.footprint_min_um = at(0.01) * unit_m * 1e6;
        s.footprint_max_um = at(0.99) * unit_m * 1e6;
        if (h.cameraKnown()) s.viewing_distance_m = at(0.01) / h.pixel_angle_rad * unit_m;
        s.environment_radiance = moment_sum / static_cast<double>(footprints.size());
    }
    // The map keeps the rest of the light as M_L azimuthal orders over J
    // cells: it cannot show features narrower than ~ 180 / M_L degrees.
    s.environment_sharpness_deg = 180.0 / std::max(1, h.orders);
    return s;
}

EffectPlan plan(const Recipe& recipe, const Scene& scene, Preset preset, const PlanSceneOptions& options) {
    return paintlab::plan(recipe, summariseScene(scene, options), preset);
}

}  // namespace paintlab::raymaps
