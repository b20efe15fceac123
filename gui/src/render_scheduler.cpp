#include "render_scheduler.h"

#include "brdf_plan_scene.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/display_image.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/planned_relight.h"
#include "paintlab/raymaps/relight.h"

#include <chrono>
#include <exception>
#include <utility>

namespace paintlab::gui {

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The relit image as the screen shows it (the same tone map as the CLI's PNG).
QImage displayImage(const raymaps::RgbImage& image, double exposure_ev) {
    const std::vector<std::uint8_t> bytes = raymaps::toDisplayRgb8(image, exposure_ev);
    QImage out(image.width, image.height, QImage::Format_RGB888);
    const auto row_bytes = static_cast<std::size_t>(image.width) * 3;
    for (int y = 0; y < image.height; ++y)
        std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(row_bytes * static_cast<std::size_t>(y)),
                    row_bytes, out.scanLine(y));
    return out;
}

}  // namespace

const raymaps::RelightInput& OpenRayMap::input() const {
    const std::lock_guard lock(m_mutex);
    if (!m_input) m_input.emplace(*m_map);
    return *m_input;
}

const PlanScene& OpenRayMap::planScene() const {
    const std::lock_guard lock(m_mutex);
    if (!m_plan_scene) m_plan_scene = raymaps::summariseRayMap(*m_map);
    return *m_plan_scene;
}

RenderScheduler::RenderScheduler(QObject* parent) : QObject(parent) {
    qRegisterMetaType<paintlab::gui::RenderResult>();
    m_pool.setMaxThreadCount(1);
}

RenderScheduler::~RenderScheduler() {
    m_pending.reset();
    m_latest->fetch_add(1);  // cancels the running job at its next progress check
    m_pool.waitForDone();
}

void RenderScheduler::setRayMap(std::shared_ptr<const raymaps::RayMap> map) {
    m_map = map ? std::make_shared<const OpenRayMap>(std::move(map)) : nullptr;
}

quint64 RenderScheduler::request(const Recipe& recipe, Preset preset) {
    const quint64 generation = m_latest->fetch_add(1) + 1;
    Job job{generation, recipe, preset, m_follow_plan};
    if (m_running) {
        m_pending = std::move(job);  // replaces an older pending request
    } else {
        start(std::move(job));
    }
    return generation;
}

void RenderScheduler::start(Job job) {
    m_running = true;
    const auto latest = m_latest;
    const auto map = m_map;
    const double exposure_ev = m_exposure_ev;
    m_pool.start([this, latest, map, exposure_ev, job = std::move(job)]() {
        std::optional<RenderResult> result;
        QString error;
        try {
            const auto alive = [&](double /*fraction*/) { return latest->load() == job.generation; };
            RenderResult r;
            r.generation = job.generation;
            r.preset = job.preset;
            r.follow_plan = job.follow_plan;
            FastModelSettings settings = presetSettings(job.preset);
            auto t0 = std::chrono::steady_clock::now();
            if (job.follow_plan) {
                const PlanScene& scene = map ? map->planScene() : brdfPlanScene();
                r.plan_scene = map ? QObject::tr("the ray map %1")
                                         .arg(QString::fromStdString(map->map()->path().filename().string()))
                                   : QString::fromStdString(scene.source);
                r.plan = plan(job.recipe, scene, job.preset);
                settings = raymaps::plannedSettings(*r.plan);
                r.plan_ms = millisecondsSince(t0);
            }
            t0 = std::chrono::steady_clock::now();
            r.brdf = std::make_shared<const LayeredBrdf>(computeLayeredBrdf(job.recipe, settings, alive));
            r.brdf_ms = millisecondsSince(t0);
            if (map && alive(1.0)) {
                t0 = std::chrono::steady_clock::now();
                const raymaps::RelightTables tables(*r.brdf, map->map()->header().cells,
                                                    map->map()->header().orders);
                r.tables_ms = millisecondsSince(t0);
                // The first relight of a map includes decoding its records (once per map).
                t0 = std::chrono::steady_clock::now();
                raymaps::RgbImage image = raymaps::relight(map->input(), tables);
                r.relight_ms = millisecondsSince(t0);
                r.sparkle_deferred = r.plan && r.plan->sparkle && job.preset == Preset::Preview;
                if (r.plan && r.plan->sparkle && !r.sparkle_deferred && alive(1.0)) {
                    t0 = std::chrono::steady_clock::now();
                    raymaps::addRecipeSparkle(*map->map(), job.recipe, image);
                    r.sparkle = true;
                    r.sparkle_ms = millisecondsSince(t0);
                }
                r.image = displayImage(image, exposure_ev);
            }
            if (alive(1.0)) result = std::move(r);
        } catch (const Error& e) {
            // "cancelled" when a newer request overtook this one; anything else is real.
            if (latest->load() == job.generation) error = QString::fromUtf8(e.what());
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        const quint64 generation = job.generation;
        QMetaObject::invokeMethod(
            this, [this, generation, result, error]() { onJobDone(generation, result, error); },
            Qt::QueuedConnection);
    });
}

void RenderScheduler::onJobDone(quint64 generation, const std::optional<RenderResult>& result,
                                const QString& error) {
    m_running = false;
    if (result && result->generation == m_latest->load()) emit finished(*result);
    if (!error.isEmpty()) emit failed(generation, error);
    if (m_pending) {
        Job next = std::move(*m_pending);
        m_pending.reset();
        start(std::move(next));
    } else {
        emit becameIdle();
    }
}

}  // namespace paintlab::gui
