#pragma once
// Plot data computed off the GUI thread, newest request first: work runs on
// one worker thread and returns what the GUI thread then applies (VTK calls
// only). A request made while another computes waits as the one pending
// request, replaced by any newer one; the finished result is still applied
// (it is newer than what is shown) before the pending work starts, so a
// dragged slider keeps the plots moving without queueing up stale work.

#include <QObject>
#include <QString>
#include <QThreadPool>

#include <functional>
#include <optional>

namespace paintlab::gui {

class LatestJob : public QObject {
    Q_OBJECT
public:
    // Applied on the GUI thread with the result of a Work.
    using Apply = std::function<void()>;
    // Runs on the worker; must not touch widgets. May throw (failed() then).
    using Work = std::function<Apply()>;

    explicit LatestJob(QObject* parent = nullptr);
    // Waits for the running work (plot data takes milliseconds); pending work is dropped.
    ~LatestJob() override;
    LatestJob(const LatestJob&) = delete;
    LatestJob& operator=(const LatestJob&) = delete;
    LatestJob(LatestJob&&) = delete;
    LatestJob& operator=(LatestJob&&) = delete;

    void run(Work work);
    bool busy() const { return m_running || m_pending.has_value(); }

signals:
    void applied();
    void failed(const QString& message);
    // Nothing is computing or pending any more.
    void becameIdle();

private:
    void start(Work work);
    QThreadPool m_pool;
    bool m_running = false;
    std::optional<Work> m_pending;
};

}  // namespace paintlab::gui
