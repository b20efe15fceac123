#include "plot_widget.h"

#include "file_output.h"

#include "plot_render_thread.h"

#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"

#include <QElapsedTimer>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QPainter>

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::gui {

// Everything here belongs to the render thread: created, used and destroyed there.
struct PlotWidget::Gl {
    QOpenGLContext context;
    std::unique_ptr<QOpenGLFramebufferObject> framebuffer;
    vtkNew<vtkGenericOpenGLRenderWindow> window;
};

PlotWidget::PlotWidget(QWidget* parent) : QWidget(parent) {
    setMinimumSize(320, 240);
    setAttribute(Qt::WA_OpaquePaintEvent);  // paintEvent covers every pixel
    m_surface = new QOffscreenSurface(nullptr, this);
    m_surface->setFormat(QSurfaceFormat::defaultFormat());
    m_surface->create();
    runOnRenderThread([this] {
        auto gl = std::make_unique<Gl>();
        gl->context.setFormat(QSurfaceFormat::defaultFormat());
        if (!gl->context.create() || !gl->context.makeCurrent(m_surface)) {
            m_failure = tr("OpenGL %1.%2 is not available for the plots")
                            .arg(QSurfaceFormat::defaultFormat().majorVersion())
                            .arg(QSurfaceFormat::defaultFormat().minorVersion());
        } else {
            // Qt owns the context; VTK draws into whatever framebuffer is bound
            // when it renders (ours) and loads its GL functions from this context.
            vtkGenericOpenGLRenderWindow* w = gl->window;
            w->SetOwnContext(0);
            w->SetReadyForRendering(true);
            w->SetIsCurrent(true);
            w->SetFrameBlitModeToBlitToCurrent();
            // No multisampling: under Mesa's software rasteriser 8x MSAA made
            // every frame 3-4x slower (a chart: ~100 ms instead of ~25 ms); VTK's
            // 2D lines and text are smoothed anyway.
            w->SetMultiSamples(0);
            w->InitializeFromCurrentContext();
        }
        m_gl = std::move(gl);
    });
}

PlotWidget::~PlotWidget() {
    // Subclasses have destroyed their VTK objects on the render thread; the
    // window gives its GL resources back while its context is still current.
    runOnRenderThread([this] {
        if (m_failure.isEmpty()) m_gl->window->Finalize();
        m_gl->framebuffer.reset();
        m_gl->context.doneCurrent();
        m_gl.reset();
    });
}

vtkGenericOpenGLRenderWindow* PlotWidget::renderWindow() const { return m_gl->window; }

void PlotWidget::onRenderThread(std::function<void()> vtk_work) {
    PlotRenderThread::instance().post([this, work = std::move(vtk_work)] {
        if (m_failure.isEmpty()) m_gl->context.makeCurrent(m_surface);
        work();
    });
    scheduleRender();
}

void PlotWidget::runOnRenderThread(const std::function<void()>& vtk_work) const {
    PlotRenderThread::instance().run([this, &vtk_work] {
        if (m_gl && m_failure.isEmpty()) m_gl->context.makeCurrent(m_surface);
        vtk_work();
    });
}

void PlotWidget::noteSize() {
    const double ratio = devicePixelRatioF();
    const QSize size = this->size().expandedTo(minimumSize());
    m_pixel_ratio = ratio;
    m_width_px = static_cast<int>(size.width() * ratio);
    m_height_px = static_cast<int>(size.height() * ratio);
}

void PlotWidget::scheduleRender() {
    // A hidden plot (another tab) is drawn when it is shown, not on every change.
    if (!isVisible()) {
        m_dirty_while_hidden = true;
        return;
    }
    noteSize();
    if (m_render_queued.exchange(true)) return;  // the queued one will draw the latest state
    PlotRenderThread::instance().post([this] {
        m_render_queued = false;
        const QImage image = drawNow();
        // Delivered on the GUI thread; dropped if the widget is gone by then.
        QMetaObject::invokeMethod(
            this, [this, image] { showImage(image); }, Qt::QueuedConnection);
    });
}

QSize PlotWidget::devicePixels() const {
    return {std::max(1, m_width_px.load()), std::max(1, m_height_px.load())};
}

QImage PlotWidget::drawNow() {
    if (!m_failure.isEmpty()) return {};
    QElapsedTimer timer;
    timer.start();
    Gl& gl = *m_gl;
    if (!gl.context.makeCurrent(m_surface)) return {};
    const QSize size = devicePixels();
    if (!gl.framebuffer || gl.framebuffer->size() != size)
        gl.framebuffer =
            std::make_unique<QOpenGLFramebufferObject>(size, QOpenGLFramebufferObject::CombinedDepthStencil);
    gl.framebuffer->bind();
    vtkGenericOpenGLRenderWindow* w = gl.window;
    w->SetSize(size.width(), size.height());
    w->SetIsCurrent(true);
    // Other plots' windows share nothing with this one, but Qt binds and
    // recreates framebuffers behind VTK's state cache: record it afresh.
    vtkOpenGLState* state = w->GetState();
    state->Reset();
    state->Push();
    w->Render();
    state->Pop();
    QImage image = gl.framebuffer->toImage(true);  // top row first; also waits for the rasteriser
    gl.framebuffer->release();
    // VTK's 2D charts leave alpha at 0 where they draw no ink, over colour
    // that is already the background's: the plot is opaque, as a
    // QOpenGLWidget showed it, so the alpha channel is dropped, not applied.
    switch (image.format()) {
    case QImage::Format_RGBA8888:
    case QImage::Format_RGBA8888_Premultiplied:
        image.reinterpretAsFormat(QImage::Format_RGBX8888);
        break;
    case QImage::Format_ARGB32:
    case QImage::Format_ARGB32_Premultiplied:
        image.reinterpretAsFormat(QImage::Format_RGB32);
        break;
    default:
        break;
    }
    image.setDevicePixelRatio(m_pixel_ratio.load());
    m_paint_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
    return image;
}

void PlotWidget::showImage(const QImage& image) {
    m_image = image;
    update();
}

QImage PlotWidget::renderImage() {
    noteSize();
    QImage image;
    runOnRenderThread([this, &image] { image = drawNow(); });
    showImage(image);
    return image;
}

void PlotWidget::paintEvent(QPaintEvent* /*event*/) {
    QElapsedTimer timer;
    timer.start();
    QPainter painter(this);
    if (m_image.isNull()) {
        painter.fillRect(rect(), Qt::white);
        if (!m_failure.isEmpty()) painter.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, m_failure);
    } else {
        // Until the drawing at a new size arrives, the last one is stretched to fit.
        painter.drawImage(rect(), m_image);
    }
    m_show_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

void PlotWidget::resizeEvent(QResizeEvent* event) {
    QWidget::resizeEvent(event);
    scheduleRender();
}

void PlotWidget::showEvent(QShowEvent* event) {
    QWidget::showEvent(event);
    if (m_dirty_while_hidden || m_image.isNull()) {
        m_dirty_while_hidden = false;
        scheduleRender();
    }
}

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

void PlotWidget::showChart(vtkContextView* view, vtkChartXY* chart) const {
    view->SetRenderWindow(renderWindow());
    view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
    view->GetScene()->AddItem(chart);
    useReadableFont(chart);
}

bool PlotWidget::exportPng(const QString& path) { return saveImageAtomically(renderImage(), path); }

bool PlotWidget::writeCsv(const QString& path, const QStringList& header,
                          const std::vector<QStringList>& rows) {
    const auto line = [](const QStringList& cells) {
        std::vector<std::string> fields;
        fields.reserve(static_cast<std::size_t>(cells.size()));
        for (const QString& cell : cells) fields.push_back(cell.toStdString());
        return io::csvJoin(fields);
    };
    std::string text = line(header);
    for (const QStringList& row : rows) text += line(row);
    return writeFileAtomically(path, text);
}

QString PlotWidget::csvNumber(double value) {
    return QString::fromStdString(io::formatNumber(value, io::NumberFormat::Digits17));
}

QString PlotWidget::csvText(const QString& text) {
    return QString::fromStdString(io::csvField(text.toStdString()));
}

}  // namespace paintlab::gui
