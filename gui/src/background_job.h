#pragma once
// One job at a time on a thread of its own, for work that reports progress
// and can be cancelled (a fit, an appearance export): the job's progress and
// its end are delivered on the GUI thread, never after this object is gone.
// Destroying it cancels the job and waits for its thread.

#include <QObject>

#include <atomic>
#include <functional>
#include <memory>

class QThread;

namespace paintlab::gui {

class BackgroundJob : public QObject {
public:
    explicit BackgroundJob(QObject* parent = nullptr);
    ~BackgroundJob() override;
    BackgroundJob(const BackgroundJob&) = delete;
    BackgroundJob& operator=(const BackgroundJob&) = delete;
    BackgroundJob(BackgroundJob&&) = delete;
    BackgroundJob& operator=(BackgroundJob&&) = delete;

    bool running() const { return m_thread != nullptr; }
    // Asks the running job to stop (it reads the flag at its next progress step).
    void cancel();
    // Waits for the job's thread (tests, shutdown); its end is still delivered.
    void wait();

protected:
    // The job's body gets the cancel flag and returns what to run on the GUI
    // thread once the thread is done (emitting the job's result signal).
    using Work = std::function<std::function<void()>(const std::atomic<bool>& cancel)>;
    // Starts the job on a low-priority thread; false if one is running.
    bool startJob(Work work);
    // From the job's thread: runs `f` on the GUI thread unless this object is gone by then.
    void post(std::function<void()> f);

private:
    void threadDone();

    QThread* m_thread = nullptr;
    std::shared_ptr<std::atomic<bool>> m_cancel;
};

}  // namespace paintlab::gui
