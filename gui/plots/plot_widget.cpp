#include "plot_widget.h"

#include <QElapsedTimer>
#include <QImage>
#include <QOpenGLContext>
#include <QSaveFile>
#include <QTextStream>

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkTextProperty.h>

#include <filesystem>

namespace paintlab::gui {

struct PlotWidget::Vtk {
    vtkNew<vtkGenericOpenGLRenderWindow> window;
};

PlotWidget::PlotWidget(QWidget* parent) : QOpenGLWidget(parent), m_vtk(std::make_unique<Vtk>()) {
    setMinimumSize(320, 240);
}

PlotWidget::~PlotWidget() {
    // QOpenGLWidget's own destructor, which runs after this one, destroys the
    // context: its aboutToBeDestroyed must not reach this half-destroyed widget.
    if (context() != nullptr) disconnect(context(), nullptr, this, nullptr);
    makeCurrent();  // VTK releases its GL resources in the widget's context
    m_vtk->window->Finalize();
    m_vtk.reset();
    doneCurrent();
}

vtkGenericOpenGLRenderWindow* PlotWidget::renderWindow() const { return m_vtk->window; }

void PlotWidget::useReadableFont(vtkChartXY* chart) {
    static const char* const kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    std::error_code error;
    if (!std::filesystem::exists(kFont, error)) return;
    const auto use = [](vtkTextProperty* text) {
        text->SetFontFamily(VTK_FONT_FILE);
        text->SetFontFile(kFont);
    };
    // The axes' numbers only: titles and legends keep the built-in font, whose
    // letters read well (DejaVu's thin l and d strokes fade at these sizes).
    for (int axis = vtkAxis::LEFT; axis <= vtkAxis::TOP; ++axis)
        use(chart->GetAxis(axis)->GetLabelProperties());
}

void PlotWidget::initializeGL() {
    // Qt owns the context; VTK draws into whatever framebuffer is bound when
    // it renders (the widget's) and loads its GL functions from this context.
    vtkGenericOpenGLRenderWindow* w = m_vtk->window;
    w->SetOwnContext(0);
    w->SetReadyForRendering(true);
    w->SetIsCurrent(true);
    w->SetFrameBlitModeToBlitToCurrent();
    // No multisampling: under Mesa's software rasteriser (Xvfb, CI) 8x MSAA
    // made every frame 3-4x slower (a chart: ~100 ms instead of ~25 ms), past
    // the GUI thread's 50 ms; VTK's 2D lines and text are smoothed anyway.
    w->SetMultiSamples(0);
    w->InitializeFromCurrentContext();
    // Floating or re-docking the dock moves the widget to another top-level
    // window: Qt destroys this context and calls initializeGL again with a new
    // one. VTK's shaders, buffers and glyph textures belong to the old context
    // and are given back while it is still current (as VTK's own
    // QVTKOpenGLNativeWidget does), or the new context would use dead handles.
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &PlotWidget::releaseGraphicsResources,
            Qt::UniqueConnection);
}

void PlotWidget::releaseGraphicsResources() {
    makeCurrent();
    m_vtk->window->ReleaseGraphicsResources(m_vtk->window);
    doneCurrent();
}

void PlotWidget::resizeGL(int w, int h) {
    const double ratio = devicePixelRatioF();
    m_vtk->window->SetSize(static_cast<int>(w * ratio), static_cast<int>(h * ratio));
}

void PlotWidget::paintGL() {
    QElapsedTimer timer;
    timer.start();
    vtkGenericOpenGLRenderWindow* w = m_vtk->window;
    w->SetIsCurrent(true);
    // Qt changes GL state (the bound framebuffer is recreated on resize, for
    // instance) behind VTK's cache: record it afresh, and give it back as found.
    vtkOpenGLState* state = w->GetState();
    state->Reset();
    state->Push();
    w->Render();
    state->Pop();
    m_paint_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

QImage PlotWidget::renderImage() { return grabFramebuffer(); }

bool PlotWidget::exportPng(const QString& path) {
    const QImage image = renderImage();
    if (image.isNull()) return false;
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly)) return false;
    if (!image.save(&file, "PNG")) {
        file.cancelWriting();
        return false;
    }
    return file.commit();
}

bool PlotWidget::writeCsv(const QString& path, const QStringList& header,
                          const std::vector<QStringList>& rows) {
    QSaveFile file(path);  // atomic: the old file stays until the new one is complete
    if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) return false;
    QTextStream out(&file);
    out << header.join(',') << '\n';
    for (const QStringList& row : rows) out << row.join(',') << '\n';
    out.flush();
    if (out.status() != QTextStream::Ok) {
        file.cancelWriting();
        return false;
    }
    return file.commit();
}

QString PlotWidget::csvNumber(double value) { return QString::number(value, 'g', 17); }

QString PlotWidget::csvText(const QString& text) {
    if (!text.contains(',') && !text.contains('"') && !text.contains('\n')) return text;
    QString quoted = text;
    quoted.replace('"', QStringLiteral("\"\""));
    return '"' + quoted + '"';
}

}  // namespace paintlab::gui
