// The brute-force reference renderer (reference.h).

#include "path_tracer.h"
#include "sampling.h"
#include "scene_tracer.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/environment_map.h"
#include "paintlab/raymaps/reference.h"
#include "paintlab/raymaps/scene_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <mutex>

namespace paintlab::raymaps {

ReferenceImage renderReference(const Scene& scene, const RelightTables& tables,
                               const ReferenceSettings& settings, const RayMapProgress& progress) {
    if (settings.samples_per_pixel < 2 || settings.samples_per_pixel > 1 << 20)
        throw InputError("<argument>", "samples_per_pixel", "must be in [2, 1048576]");
    if (settings.max_depth < 1 || settings.max_depth > 64)
        throw InputError("<argument>", "max_depth", "must be in [1, 64]");
    const SceneGeometry geometry = buildSceneGeometry(scene);
    const EnvironmentMap environment = EnvironmentMap::load(scene.environment);
    const SceneTracer tracer(geometry);
    PathTracer pt(scene, tracer, environment, settings.max_depth);
    pt.setPaint(&tables);
    const PinholeCamera camera(scene.camera);
    const int width = scene.camera.width;
    const int height = scene.camera.height;
    ReferenceImage out;
    out.mean.width = width;
    out.mean.height = height;
    const std::size_t values = 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    out.mean.rgb.assign(values, 0.0F);
    out.variance_of_mean.assign(values, 0.0F);
    const int n = settings.samples_per_pixel;
    std::atomic<int> rows_done{0};
    std::atomic<bool> cancelled{false};
    std::mutex progress_mutex;  // the callback need not be thread safe
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y != range.end() && !cancelled.load(); ++y) {
            for (int x = 0; x < width; ++x) {
                const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) +
                                   static_cast<std::uint64_t>(x);
                Rng rng(settings.seed, pixel, 1);
                Rgb3 sum = Rgb3::Zero();
                Rgb3 sum2 = Rgb3::Zero();
                for (int s = 0; s < n; ++s) {
                    const Vec3 dir = camera.direction(x + rng.uniform(), y + rng.uniform());
                    const Rgb3 l = pt.radiance(camera.origin(), dir, rng, true);
                    sum += l;
                    sum2 += l.cwiseProduct(l);
                }
                const Rgb3 mean = sum / n;
                const Rgb3 var = ((sum2 / n - mean.cwiseProduct(mean)) * (static_cast<double>(n) / (n - 1)))
                                     .cwiseMax(0.0) /
                                 n;
                const std::size_t at = 3 * static_cast<std::size_t>(pixel);
                for (int c = 0; c < 3; ++c) {
                    out.mean.rgb[at + static_cast<std::size_t>(c)] = static_cast<float>(mean[c]);
                    out.variance_of_mean[at + static_cast<std::size_t>(c)] = static_cast<float>(var[c]);
                }
            }
            const int done = ++rows_done;
            if (progress) {
                const std::scoped_lock lock(progress_mutex);
                if (!progress(static_cast<double>(done) / height)) cancelled = true;
            }
        }
    });
    if (cancelled.load()) throw Error("cancelled");
    return out;
}

}  // namespace paintlab::raymaps
