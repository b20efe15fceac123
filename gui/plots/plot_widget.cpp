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
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContext2D.h>
#include <vtkContextItem.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::gui {

namespace {

constexpr const char* kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Drawn after the chart in the same scene: records where the chart put its
// parts in this drawing (PlotWidget::chartLayout).
class LayoutProbe : public vtkContextItem {
public:
    // As vtkStandardNewMacro (see ab_chart.cpp for why not the macro).
    static LayoutProbe* New() {
        auto* item = new LayoutProbe;
        item->InitializeObjectBase();
        return item;
    }

    vtkChartXY* chart = nullptr;
    PlotWidget::ChartLayout layout;

    bool Paint(vtkContext2D* painter) override {
        if (chart == nullptr) return false;
        PlotWidget::ChartLayout l;
        if (vtkContextScene* scene = GetScene())
            l.scene = QRectF(0, 0, scene->GetSceneWidth(), scene->GetSceneHeight());
        vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
        vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
        const auto d = [](float v) { return static_cast<double>(v); };
        l.data = QRectF(QPointF(d(x->GetPoint1()[0]), d(y->GetPoint1()[1])),
                        QPointF(d(x->GetPoint2()[0]), d(y->GetPoint2()[1])))
                     .normalized();
        l.left_min = y->GetUnscaledMinimum();
        l.left_max = y->GetUnscaledMaximum();
        l.bottom_min = x->GetUnscaledMinimum();
        l.bottom_max = x->GetUnscaledMaximum();
        l.left_log = y->GetLogScaleActive();
        l.left_title = QString::fromStdString(y->GetTitle());
        l.title = QString::fromStdString(chart->GetTitle());
        if (!l.left_title.isEmpty()) {
            painter->ApplyTextProp(y->GetTitleProperties());
            float bounds[4] = {0, 0, 0, 0};
            painter->ComputeStringBounds(y->GetTitle(), bounds);
            l.left_title_px = d(std::max(bounds[2], bounds[3]));
        }
        if (chart->GetShowLegend()) {
            vtkChartLegend* legend = chart->GetLegend();
            const vtkRectf r = legend->GetBoundingRect(painter);  // in scene pixels, from its Point
            l.legend = QRectF(d(r.GetX()), d(r.GetY()), d(r.GetWidth()), d(r.GetHeight()));
            for (vtkIdType k = 0; k < chart->GetNumberOfPlots(); ++k) {
                vtkPlot* plot = chart->GetPlot(k);
                if (plot->GetVisible() && plot->GetLegendVisibility())
                    l.legend_labels << QString::fromStdString(plot->GetLabel());
            }
        }
        layout = l;
        return true;
    }

protected:
    LayoutProbe() = default;
    ~LayoutProbe() override = default;
};

}  // namespace

// Everything here belongs to the render thread: created, used and destroyed there.
struct PlotWidget::Gl {
    QOpenGLContext context;
    std::unique_ptr<QOpenGLFramebufferObject> framebuffer;
    vtkNew<vtkGenericOpenGLRenderWindow> window;
    vtkNew<LayoutProbe> probe;  // of the chart shown (showChart), if any
};

PlotWidget::PlotWidget(QWidget* parent) : QWidget(parent) {
    setMinimumSize(200, 100);               // a plot fits a laptop's bottom dock
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
    layoutForSize(size.width(), size.height());
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

void PlotWidget::useUnicodeFont(vtkTextProperty* text) {
    std::error_code error;
    if (!std::filesystem::exists(kDejaVuSans, error)) return;
    text->SetFontFamily(VTK_FONT_FILE);
    text->SetFontFile(kDejaVuSans);
}

void PlotWidget::useReadableFont(vtkChartXY* chart) {
    // The axes' numbers only: titles and legends keep the built-in font, whose
    // letters read well (DejaVu's thin l and d strokes fade at these sizes).
    for (int axis = vtkAxis::LEFT; axis <= vtkAxis::TOP; ++axis)
        useUnicodeFont(chart->GetAxis(axis)->GetLabelProperties());
}

void PlotWidget::showChart(vtkContextView* view, vtkChartXY* chart, LegendPlace legend) const {
    view->SetRenderWindow(renderWindow());
    view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
    view->GetScene()->AddItem(chart);
    useReadableFont(chart);
    placeLegend(chart, legend);
    m_gl->probe->chart = chart;
    view->GetScene()->AddItem(m_gl->probe);  // after the chart: sees this drawing's layout
}

void PlotWidget::placeLegend(vtkChartXY* chart, LegendPlace legend) {
    // Outside the axes' box (vtkChartXY makes room for a legend that is not
    // inline), so that it never hides a curve's peak.
    vtkChartLegend* box = chart->GetLegend();
    box->SetInline(false);
    box->SetHorizontalAlignment(legend == LegendPlace::Right ? vtkChartLegend::RIGHT
                                                             : vtkChartLegend::CENTER);
    box->SetVerticalAlignment(legend == LegendPlace::Right ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
}

void PlotWidget::setValueAxis(vtkChartXY* chart, bool log_scale, double lo, double hi, double decades) {
    vtkAxis* axis = chart->GetAxis(vtkAxis::LEFT);
    if (!log_scale || !(hi > 0.0)) {
        axis->SetLogScale(false);
        axis->SetBehavior(vtkAxis::AUTO);
        return;
    }
    const double top = hi * 1.5;  // room above the peak: half a tick on a log axis
    const double bottom = std::max(lo > 0.0 ? lo / 1.5 : 0.0, hi * std::pow(10.0, -decades));
    axis->SetBehavior(vtkAxis::FIXED);
    axis->SetLogScale(true);
    axis->SetUnscaledRange(bottom, top);
}

PlotWidget::ChartLayout PlotWidget::chartLayout() const {
    ChartLayout layout;
    runOnRenderThread([this, &layout] {
        if (m_gl) layout = m_gl->probe->layout;
    });
    return layout;
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
