#pragma once
// Recomputes the paint on a worker thread whenever the recipe changes: the
// fast model's LayeredBrdf, then, when a ray map is open, its relight. The
// newest request wins: a request made while another computes cancels it
// (the fast model's progress callback returns false) and waits as the one
// pending request, replaced by any newer one, so a dragged slider never
// queues up stale work and the GUI thread never waits for the engine.

#include "paintlab/engine/layered_brdf.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/raymap.h"

#include <QImage>
#include <QObject>
#include <QString>
#include <QThreadPool>

#include <atomic>
#include <memory>
#include <optional>

namespace paintlab::gui {

struct RenderResult {
    quint64 generation = 0;
    Preset preset = Preset::Standard;
    std::shared_ptr<const LayeredBrdf> brdf;
    QImage image;  // null without a ray map
    double brdf_ms = 0.0;
    double tables_ms = 0.0;
    double relight_ms = 0.0;
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
    const std::shared_ptr<const raymaps::RayMap>& rayMap() const { return m_map; }
    void setExposure(double exposure_ev) { m_exposure_ev = exposure_ev; }

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
    };
    void start(Job job);
    void onJobDone(quint64 generation, const std::optional<RenderResult>& result, const QString& error);

    QThreadPool m_pool;  // one thread: the engine parallelises inside (TBB)
    std::shared_ptr<std::atomic<quint64>> m_latest = std::make_shared<std::atomic<quint64>>(0);
    std::shared_ptr<const raymaps::RayMap> m_map;
    double m_exposure_ev = 0.0;
    bool m_running = false;
    std::optional<Job> m_pending;
};

}  // namespace paintlab::gui

Q_DECLARE_METATYPE(paintlab::gui::RenderResult)
