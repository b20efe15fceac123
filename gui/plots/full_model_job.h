#pragma once
// The full model (Monte Carlo, explicit flakes) tabulated on the fast model's
// basis (engine mc::tabulateMonteCarlo) off the GUI thread, for the Plots
// dock's "Compare with full model". One run at a time on its own worker
// thread; a new request cancels the running one (through the progress
// callback, which the engine calls after every round of paths) and starts
// when it has stopped: the newest request wins, and a cancelled or replaced
// run delivers nothing. Progress is posted to the GUI thread when its percent
// changes.

#include <QObject>
#include <QString>
#include <QThreadPool>

#include <atomic>
#include <cstdint>
#include <memory>

namespace paintlab {
class LayeredBrdf;
struct Recipe;
}  // namespace paintlab

namespace paintlab::gui {

class FullModelJob : public QObject {
    Q_OBJECT
public:
    struct Result {
        std::shared_ptr<const LayeredBrdf> brdf;
        std::int64_t paths = 0;
        double seconds = 0.0;  // the full model's own time (tabulateMonteCarlo's McTable::seconds)
    };

    explicit FullModelJob(QObject* parent = nullptr);
    // Cancels the running run and waits for it to stop (about one round of paths).
    ~FullModelJob() override;
    FullModelJob(const FullModelJob&) = delete;
    FullModelJob& operator=(const FullModelJob&) = delete;
    FullModelJob(FullModelJob&&) = delete;
    FullModelJob& operator=(FullModelJob&&) = delete;

    // Explicit flakes on the preview preset's grid, max_seconds = budget_seconds
    // (shared by the grid's bands x nodes as tabulateMonteCarlo does).
    void start(const Recipe& recipe, double budget_seconds);
    void cancel();
    bool busy() const { return m_busy; }

signals:
    void progress(int percent);
    void finished(const paintlab::gui::FullModelJob::Result& result);
    // The engine's message (an InputError names the field).
    void failed(const QString& message);
    // The newest run stopped on cancel(); nothing is delivered for it.
    void cancelled();

private:
    QThreadPool m_pool;
    bool m_busy = false;
    quint64 m_generation = 0;                     // of the newest request; older runs' results are dropped
    std::shared_ptr<std::atomic<bool>> m_cancel;  // of the running run
};

}  // namespace paintlab::gui
