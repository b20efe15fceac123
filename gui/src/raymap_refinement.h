#pragma once
// The open scene's ray map refined in the background while the user works
// (issue 26, part 4; docs/RAYMAPS.md, "Progressive refinement"): a worker
// thread at the lowest priority (nice 19), its ray tracing in a one-thread TBB arena (the
// relight of the edited recipe keeps the machine's other threads), adds
// passes to a ProgressiveRayMap; after each pass from the second on it
// writes the average, reads it back into memory, and hands it to the GUI
// thread (passLanded), which relights the current recipe in it. The noise of
// the relit paint is estimated from the map itself (noise_estimate.h: the
// average of all passes against the odd passes' alone) with the recipe last
// given by setRecipe; refinement stops when it is at most the target, or at
// the pass budget. The GUI thread never waits for a pass: cancel() and the
// destructor stop the pass under way within a band of rows.

#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/raymap.h"

#include <QObject>
#include <QString>

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace paintlab::gui {

class RayMapRefinement : public QObject {
    Q_OBJECT
public:
    struct Limits {
        int max_passes = 64;          // the pass budget (the map opened holds 1)
        double target_noise = 0.01;   // stop at this estimated per-pixel noise (worst channel)
        bool lowest_priority = true;  // the worker at nice 19 (tests turn it off on loaded machines)
        // The refined map's image size: that of the map the workstation opened
        // (it may follow the view, raymap_resolution.h); 0: the scene camera's.
        int camera_width = 0;
        int camera_height = 0;
    };

    explicit RayMapRefinement(QObject* parent = nullptr);
    // Cancels the pass under way and waits for the worker (at most a band of rows).
    ~RayMapRefinement() override;
    RayMapRefinement(const RayMapRefinement&) = delete;
    RayMapRefinement& operator=(const RayMapRefinement&) = delete;
    RayMapRefinement(RayMapRefinement&&) = delete;
    RayMapRefinement& operator=(RayMapRefinement&&) = delete;

    // Refines `scene`'s map (RayMapSettings{} as the workstation traces it)
    // into `out`, replaced after each pass; cancels any refinement before.
    // Errors (a bad scene, a full disk) end it with failed().
    void start(const std::filesystem::path& scene, const std::filesystem::path& out, Limits limits);
    void start(const std::filesystem::path& scene, const std::filesystem::path& out) {
        start(scene, out, {});
    }
    // Stops the worker without waiting for it (it ends within a band of
    // rows); no signal of the cancelled run arrives afterwards.
    void cancel();
    // The recipe whose relit paint the noise is estimated on (thread-safe;
    // the next estimate uses it). Without one, no estimate: the budget ends it.
    void setRecipe(const Recipe& recipe);

    bool running() const { return !m_done->load(); }
    int passes() const { return m_passes; }
    // Estimated noise of the last map landed (worst channel, fraction), or nullopt.
    std::optional<double> noise() const { return m_noise; }
    // "refining: pass k, noise x %" (or the end's words) for the status bar.
    QString statusText() const { return m_status; }

signals:
    // A map of `passes` passes, fully in memory (its file may be replaced).
    void passLanded(int passes, std::shared_ptr<const paintlab::raymaps::RayMap> map);
    void statusChanged(const QString& text);
    // Refinement ended: the target was met or the budget spent.
    void finished();
    void failed(const QString& message);

private:
    void run(const std::filesystem::path& scene, const std::filesystem::path& out, Limits limits,
             quint64 generation, const std::atomic<bool>& cancel);
    // On the GUI thread: a pass's map and noise estimate (negative: none).
    void landed(quint64 generation, int passes, double noise,
                const std::shared_ptr<const raymaps::RayMap>& map, bool last);
    void setStatus(const QString& text);

    void joinRetired(bool all);

    std::thread m_worker;
    std::vector<std::pair<std::thread, std::shared_ptr<std::atomic<bool>>>>
        m_retired;  // cancelled, and their done flags
    std::shared_ptr<std::atomic<bool>> m_cancel = std::make_shared<std::atomic<bool>>(false);
    std::shared_ptr<std::atomic<bool>> m_done = std::make_shared<std::atomic<bool>>(true);
    quint64 m_generation = 0;  // of the current run: signals of older runs are dropped
    std::mutex m_recipe_mutex;
    std::optional<Recipe> m_recipe;
    int m_passes = 0;
    std::optional<double> m_noise;
    QString m_status;
};

}  // namespace paintlab::gui

Q_DECLARE_METATYPE(std::shared_ptr<const paintlab::raymaps::RayMap>)
