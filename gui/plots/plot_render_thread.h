#pragma once
// The one thread on which every VTK call of the workstation's plots runs.
//
// Under Mesa's software rasteriser (Xvfb on CI, any machine without a GPU) a
// chart costs 25-70 ms to draw and a window holding a QOpenGLWidget is
// composed through OpenGL on every repaint (80-200 ms at 1,400 x 900,
// docs/PERFORMANCE.md): the GUI thread could not stay under 50 ms. So the
// plots draw into offscreen framebuffers here and the window shows the images
// as plain raster widgets (plot_widget.h).
//
// VTK is not thread-safe, and its font and shader caches are process-wide:
// every VTK object of every plot is created, changed, rendered and destroyed
// by tasks run here, one at a time, in the order they were posted. Where the
// platform cannot make OpenGL current on a second thread
// (QOpenGLContext::supportsThreadedOpenGL), or PAINTLAB_PLOTS_ON_GUI_THREAD=1
// asks for it (to measure the difference), the same tasks run on the GUI
// thread from its event loop instead.

#include <functional>

namespace paintlab::gui {

class PlotRenderThread {
public:
    // Started on first use, from the GUI thread, after the QGuiApplication;
    // stopped (after its queued tasks) when the application object is destroyed.
    static PlotRenderThread& instance();

    // Queues a task and returns at once. Tasks run in the order posted.
    void post(std::function<void()> task);
    // Queues a task and waits until it has run (with every task posted before
    // it). From the render thread itself it runs the task at once.
    void run(const std::function<void()>& task);
    // Waits for every task posted so far, then delivers the images they sent
    // to the widgets (queued calls to the GUI thread), so that QWidget::grab
    // shows the plots' latest state. GUI thread only.
    void settle();

    bool threaded() const;

private:
    PlotRenderThread() = default;
};

}  // namespace paintlab::gui
