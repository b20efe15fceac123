#pragma once
// Recomputes the paint on a worker thread whenever the recipe changes: the
// fast model's LayeredBrdf, then, when a ray map is open, its relight. The
// newest request wins: a request made while another computes cancels it
// (the fast model's progress callback returns false) and waits as the one
// pending request, replaced by any newer one, so a dragged slider never
// queues up stale work and the GUI thread never waits for the engine.
//
// With "follow the effect plan" on (the default), the worker first plans
// (engine/plan.h) for the recipe, the preset and the open ray map's lights
// and footprints (without a map: the BRDF alone, brdf_plan_scene.h), then
// runs the fast model at the plan's settings and the sparkle pass where the
// plan finds glints visible, as the CLI's `relight --plan` does
// (raymaps/planned_relight.h). Off: the preset as it is, no sparkle.
//
// Two schedulers (the edited recipe and a comparison version) can share one
// open map (shareRayMap): its records are decoded, and the plan's summary of
// it made, once.

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight_input.h"

#include <QImage>
#include <QObject>
#include <QString>
#include <QThreadPool>

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>

namespace paintlab::gui {

struct RenderResult {
    quint64 generation = 0;
    Preset preset = Preset::Standard;
    std::shared_ptr<const LayeredBrdf> brdf;
    QImage image;  // null without a ray map
    bool follow_plan = false;
    std::optional<EffectPlan> plan;  // set when the plan was followed
    QString plan_scene;              // what the plan was made for (the ray map's file, or the BRDF alone)
    bool sparkle = false;            // the sparkle pass ran on the image
    // The plan draws glints but this is a preview: left out, since the
    // sparkle pass cost 12-40x the relight on the demo scene (185-422 ms)
    // and a slider drag needs an image per edit; the standard result after
    // the release draws them.
    bool sparkle_deferred = false;
    double plan_ms = 0.0;
    double brdf_ms = 0.0;
    double tables_ms = 0.0;
    double relight_ms = 0.0;
    double sparkle_ms = 0.0;
};

// An open ray map and what is derived from it once, on first use by a
// worker (thread-safe): its decoded records and the plan's summary of it.
class OpenRayMap {
public:
    explicit OpenRayMap(std::shared_ptr<const raymaps::RayMap> map) : m_map(std::move(map)) {}
    const std::shared_ptr<const raymaps::RayMap>& map() const { return m_map; }
    // Throw InputError naming the map's file if a band is corrupt.
    const raymaps::RelightInput& input() const;
    const PlanScene& planScene() const;

private:
    std::shared_ptr<const raymaps::RayMap> m_map;
    mutable std::mutex m_mutex;
    mutable std::optional<raymaps::RelightInput> m_input;
    mutable std::optional<PlanScene> m_plan_scene;
};

class RenderScheduler : public QObject {
    Q_OBJECT
public:
    explicit RenderScheduler(QObject* parent = nullptr);
    // Cancels what is computing and waits for it (the engine checks often).
    ~RenderScheduler() override;
    RenderScheduler(const RenderScheduler&) = delete;
    RenderScheduler& operator=(const RenderScheduler&) = delete;
    RenderScheduler(RenderScheduler&&) = delete;
    RenderScheduler& operator=(RenderScheduler&&) = delete;

    // The map the paint is relit in (nullptr: BRDF only). Takes effect with the next request.
    void setRayMap(std::shared_ptr<const raymaps::RayMap> map);
    // The same open map as `other` (decoded once for both).
    void shareRayMap(const RenderScheduler& other) { m_map = other.m_map; }
    std::shared_ptr<const raymaps::RayMap> rayMap() const { return m_map ? m_map->map() : nullptr; }
    void setExposure(double exposure_ev) { m_exposure_ev = exposure_ev; }
    double exposure() const { return m_exposure_ev; }
    // Follow the effect plan (default) or run the preset as it is. Takes effect with the next request.
    void setFollowPlan(bool follow) { m_follow_plan = follow; }
    bool followPlan() const { return m_follow_plan; }

    // Returns the request's generation; results of older ones are never delivered.
    quint64 request(const Recipe& recipe, Preset preset);
    bool idle() const { return !m_running && !m_pending; }
    quint64 latestGeneration() const { return m_latest->load(); }

signals:
    void finished(const paintlab::gui::RenderResult& result);
    // The request failed (message names the field or file); the previous image stays.
    void failed(quint64 generation, const QString& message);
    // Emitted whenever nothing is computing or pending any more.
    void becameIdle();

private:
    struct Job {
        quint64 generation = 0;
        Recipe recipe;
        Preset preset = Preset::Standard;
        bool follow_plan = true;
    };
    void start(Job job);
    void onJobDone(quint64 generation, const std::optional<RenderResult>& result, const QString& error);

    QThreadPool m_pool;  // one thread: the engine parallelises inside (TBB)
    std::shared_ptr<std::atomic<quint64>> m_latest = std::make_shared<std::atomic<quint64>>(0);
    std::shared_ptr<const OpenRayMap> m_map;
    double m_exposure_ev = 0.0;
    bool m_follow_plan = true;
    bool m_running = false;
    std::optional<Job> m_pending;
};

}  // namespace paintlab::gui

Q_DECLARE_METATYPE(paintlab::gui::RenderResult)
