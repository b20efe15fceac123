#include "plot_render_thread.h"

#include <QCoreApplication>
#include <QEvent>
#include <QGuiApplication>
#include <QOpenGLContext>
#include <QThread>

namespace paintlab::gui {

namespace {

// Owns the thread and the object whose event queue holds the tasks; a child
// of the application object, so that it is stopped before Qt goes.
class RenderThreadHost : public QObject {
public:
    explicit RenderThreadHost(QObject* parent) : QObject(parent) {
        const bool wanted = qEnvironmentVariableIntValue("PAINTLAB_PLOTS_ON_GUI_THREAD") == 0;
        m_threaded = wanted && QOpenGLContext::supportsThreadedOpenGL();
        m_worker = new QObject();  // NOLINT(cppcoreguidelines-owning-memory): deleted by the thread's end
        if (!m_threaded) {
            m_worker->setParent(this);
            return;
        }
        m_thread.setObjectName(QStringLiteral("plot render"));
        m_worker->moveToThread(&m_thread);
        connect(&m_thread, &QThread::finished, m_worker, &QObject::deleteLater);
        m_thread.start();
    }
    ~RenderThreadHost() override {
        if (!m_threaded) return;
        m_thread.quit();  // after the tasks already queued
        m_thread.wait();
    }
    RenderThreadHost(const RenderThreadHost&) = delete;
    RenderThreadHost& operator=(const RenderThreadHost&) = delete;
    RenderThreadHost(RenderThreadHost&&) = delete;
    RenderThreadHost& operator=(RenderThreadHost&&) = delete;

    QObject* worker() const { return m_worker; }
    bool threaded() const { return m_threaded; }

private:
    QThread m_thread;
    QObject* m_worker = nullptr;
    bool m_threaded = false;
};

RenderThreadHost& host() {
    static RenderThreadHost* h = nullptr;
    if (h == nullptr) {
        h = new RenderThreadHost(QCoreApplication::instance());  // NOLINT(cppcoreguidelines-owning-memory):
                                                                 // owned by the application
        QObject::connect(h, &QObject::destroyed, [] { h = nullptr; });
    }
    return *h;
}

}  // namespace

PlotRenderThread& PlotRenderThread::instance() {
    static PlotRenderThread thread;
    host();  // started here, on the GUI thread
    return thread;
}

bool PlotRenderThread::threaded() const { return host().threaded(); }

void PlotRenderThread::post(std::function<void()> task) {
    QMetaObject::invokeMethod(host().worker(), std::move(task), Qt::QueuedConnection);
}

void PlotRenderThread::run(const std::function<void()>& task) {
    RenderThreadHost& h = host();
    if (QThread::currentThread() == h.worker()->thread()) {
        if (!h.threaded()) {
            // On the GUI thread: the tasks queued before this one run first, as on the render thread.
            QCoreApplication::sendPostedEvents(h.worker(), QEvent::MetaCall);
        }
        task();
        return;
    }
    QMetaObject::invokeMethod(h.worker(), task, Qt::BlockingQueuedConnection);
}

void PlotRenderThread::settle() {
    run([] {});
    // The images the finished renders sent are queued calls to the plot widgets.
    QCoreApplication::sendPostedEvents(nullptr, QEvent::MetaCall);
}

}  // namespace paintlab::gui
