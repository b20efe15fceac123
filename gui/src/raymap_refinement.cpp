// TBB before any Qt header: its profiling.h declares emit(), which Qt's
// `emit` macro would replace.
#include <tbb/task_arena.h>

#include "raymap_refinement.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/raymaps/noise_estimate.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"

#include <exception>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace paintlab::gui {

namespace {

// The worker yields to everything else on the machine: the user's edits,
// the relight, other programs (nice 19 for this thread alone; SCHED_IDLE
// starved it for minutes on a loaded machine).
void lowestPriority() {
#ifdef __linux__
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
#endif
}

}  // namespace

RayMapRefinement::RayMapRefinement(QObject* parent) : QObject(parent) {
    qRegisterMetaType<std::shared_ptr<const raymaps::RayMap>>();
}

RayMapRefinement::~RayMapRefinement() {
    cancel();
    joinRetired(true);
}

void RayMapRefinement::joinRetired(bool all) {
    for (auto it = m_retired.begin(); it != m_retired.end();) {
        if (all || it->second->load()) {
            it->first.join();
            it = m_retired.erase(it);
        } else {
            ++it;
        }
    }
}

void RayMapRefinement::cancel() {
    ++m_generation;  // what the cancelled run still posts is dropped
    m_cancel->store(true);
    if (m_worker.joinable()) m_retired.emplace_back(std::move(m_worker), m_done);
    m_done = std::make_shared<std::atomic<bool>>(true);
    joinRetired(false);
}

void RayMapRefinement::setRecipe(const Recipe& recipe) {
    const std::lock_guard lock(m_recipe_mutex);
    m_recipe = recipe;
}

void RayMapRefinement::start(const std::filesystem::path& scene, const std::filesystem::path& out,
                             Limits limits) {
    cancel();
    m_cancel = std::make_shared<std::atomic<bool>>(false);
    m_done = std::make_shared<std::atomic<bool>>(false);
    m_passes = 1;
    m_noise.reset();
    setStatus(tr("refining: pass 1"));
    m_worker = std::thread(
        [this, scene, out, limits, generation = m_generation, cancel = m_cancel, done = m_done]() {
            if (limits.lowest_priority) lowestPriority();
            try {
                // One thread: the relight of the edited recipe keeps the others.
                tbb::task_arena arena(1);
                arena.execute([&]() { run(scene, out, limits, generation, *cancel); });
            } catch (const std::exception& e) {
                if (!cancel->load()) {
                    const QString message = QString::fromUtf8(e.what());
                    QMetaObject::invokeMethod(
                        this,
                        [this, generation, message]() {
                            if (generation != m_generation) return;
                            setStatus(tr("refining failed: %1").arg(message));
                            emit failed(message);
                        },
                        Qt::QueuedConnection);
                }
            }
            done->store(true);
        });
}

void RayMapRefinement::run(const std::filesystem::path& scene, const std::filesystem::path& out,
                           Limits limits, quint64 generation, const std::atomic<bool>& cancel) {
    raymaps::Scene loaded = raymaps::loadSceneFile(scene);
    if (limits.camera_width > 0 && limits.camera_height > 0) {
        loaded.camera.width = limits.camera_width;
        loaded.camera.height = limits.camera_height;
    }
    raymaps::ProgressiveRayMap map(loaded, raymaps::RayMapSettings{});
    const auto keep_going = [&cancel](double /*fraction*/) { return !cancel.load(); };
    std::filesystem::path odd_file = out;
    odd_file += ".odd";
    for (int k = 1; k <= limits.max_passes; ++k) {
        map.addPass(keep_going);  // Error("cancelled") ends the run quietly
        if (k < 2) continue;      // pass 1 is the map the workstation opened
        map.write(out);
        std::shared_ptr<raymaps::RayMap> full(raymaps::RayMap::open(out));
        full->loadAll();  // in memory: the next pass may replace the file
        std::optional<Recipe> recipe;
        {
            const std::lock_guard lock(m_recipe_mutex);
            recipe = m_recipe;
        }
        double noise = -1.0;
        if (recipe) {
            map.writeOddPasses(odd_file);
            const auto odd = raymaps::RayMap::open(odd_file);
            const LayeredBrdf brdf = computeLayeredBrdf(*recipe, presetSettings(Preset::Preview));
            const raymaps::RelightTables tables(brdf, full->header().cells, full->header().orders);
            const raymaps::RelightInput input(*full);
            noise = raymaps::estimateProgressiveNoise(input, raymaps::relight(input, tables),
                                                      raymaps::relight(*odd, tables), k)
                        .worst();
            std::error_code ignored;
            std::filesystem::remove(odd_file, ignored);
        }
        const bool last = k == limits.max_passes || (noise >= 0.0 && noise <= limits.target_noise);
        std::shared_ptr<const raymaps::RayMap> landed_map = std::move(full);
        QMetaObject::invokeMethod(
            this,
            [this, generation, k, noise, landed_map, last]() {
                landed(generation, k, noise, landed_map, last);
            },
            Qt::QueuedConnection);
        if (last || cancel.load()) return;
    }
    // A budget below 2 passes: nothing to add to the map opened.
    QMetaObject::invokeMethod(
        this, [this, generation]() { landed(generation, 1, -1.0, nullptr, true); }, Qt::QueuedConnection);
}

void RayMapRefinement::landed(quint64 generation, int passes, double noise,
                              const std::shared_ptr<const raymaps::RayMap>& map, bool last) {
    if (generation != m_generation) return;  // a cancelled run's
    m_passes = passes;
    if (noise >= 0.0) m_noise = noise;
    const QString noise_text = m_noise ? tr(", noise %1 %").arg(100.0 * *m_noise, 0, 'f', 1) : QString();
    setStatus(last ? tr("refined: %1 passes%2").arg(passes).arg(noise_text)
                   : tr("refining: pass %1%2").arg(passes).arg(noise_text));
    if (map) emit passLanded(passes, map);
    if (last) emit finished();
}

void RayMapRefinement::setStatus(const QString& text) {
    m_status = text;
    emit statusChanged(text);
}

}  // namespace paintlab::gui
