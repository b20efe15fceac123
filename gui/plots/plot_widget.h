#pragma once
// What every VTK plot of the workstation shares. VTK draws offscreen, on the
// plot render thread (plot_render_thread.h), into a framebuffer object of a
// context of the plot's own, through a vtkGenericOpenGLRenderWindow (Debian
// 12's VTK Qt module is Qt5-only, shared/notes/debian12-stack.md, trap 1);
// the image read back is what this plain QWidget paints. The GUI thread never
// waits for VTK, and the main window holds no OpenGL widget, so Qt composes
// it in the raster backing store instead of through OpenGL.
//
// Rules for subclasses: every VTK object is created, changed, queried and
// destroyed in a task given to onRenderThread (queued; a redraw follows) or
// runOnRenderThread (waited for: construction, destruction, queries). A task
// must not read the widget's own data, which the GUI thread may change
// meanwhile: it captures a copy. Every plot exports what it shows as PNG and
// the numbers behind it as CSV.
//
// Only forward declarations of VTK types appear here; no VTK header is included.

#include <QImage>
#include <QRectF>
#include <QString>
#include <QStringList>
#include <QWidget>

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

class QOffscreenSurface;
class vtkChartXY;
class vtkContextView;
class vtkGenericOpenGLRenderWindow;
class vtkTextProperty;

namespace paintlab::gui {

class PlotWidget : public QWidget {
    Q_OBJECT
public:
    explicit PlotWidget(QWidget* parent = nullptr);
    ~PlotWidget() override;
    PlotWidget(const PlotWidget&) = delete;
    PlotWidget& operator=(const PlotWidget&) = delete;
    PlotWidget(PlotWidget&&) = delete;
    PlotWidget& operator=(PlotWidget&&) = delete;

    // The plot drawn now, at the widget's size in device pixels, with every
    // change made so far (waits for the render thread); null if OpenGL failed.
    QImage renderImage();
    // Writes renderImage() as PNG; false (and no file) if there is no image or
    // the file cannot be written.
    bool exportPng(const QString& path);
    // Writes the plotted numbers as CSV (full double precision); false (and
    // nothing half written) on failure.
    virtual bool exportCsv(const QString& path) const = 0;
    // Render-thread time of the last draw (VTK's render and the read-back), ms.
    double lastPaintMs() const { return m_paint_ms.load(); }
    // GUI-thread time of the last paintEvent (drawing the image), ms.
    double lastShowMs() const { return m_show_ms; }
    // Why there is no image, if OpenGL could not be set up (empty otherwise).
    const QString& failure() const { return m_failure; }

    // Where the chart's parts were in its last drawing (pixels, y up from the
    // bottom; empty before the first drawing or for a plot that is no 2D
    // chart), read back on the render thread: what the tests check for
    // overlap and clipping.
    struct ChartLayout {
        QRectF scene;                               // the whole drawing
        QRectF data;                                // the axes' box
        QRectF legend;                              // empty without a legend
        double left_title_px = 0;                   // length of the left axis' title along the axis
        double left_min = 0.0, left_max = 0.0;      // the left axis' range
        double bottom_min = 0.0, bottom_max = 0.0;  // the bottom axis' range
        bool left_log = false;                      // a logarithmic left axis in effect
        QStringList legend_labels;                  // of the plots shown in the legend
        QString left_title;
        QString title;  // the chart's, lines joined by '\n'
    };
    ChartLayout chartLayout() const;

signals:
    // The plotted data changed (after setBrdf and the like).
    void dataChanged();

protected:
    // Render thread only.
    vtkGenericOpenGLRenderWindow* renderWindow() const;
    // Queues VTK work (with this plot's context current) and then a redraw.
    void onRenderThread(std::function<void()> vtk_work);
    // Runs VTK work with this plot's context current and waits for it.
    void runOnRenderThread(const std::function<void()>& vtk_work) const;
    // Queues a redraw (several queued ones draw once).
    void scheduleRender();

    void paintEvent(QPaintEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;
    void showEvent(QShowEvent* event) override;

    // One CSV file: a header line and rows of already formatted cells
    // (quoted where needed), atomically replaced (QSaveFile).
    static bool writeCsv(const QString& path, const QStringList& header,
                         const std::vector<QStringList>& rows);
    static QString csvNumber(double value);  // round-trips exactly
    // The chart's axis numbers in DejaVu Sans (Debian's fonts-dejavu-core)
    // instead of VTK's built-in Arial, whose zero is drawn like a "D" at
    // chart sizes ("D.1D" for 0.10); the built-in font stays if the file is
    // missing. Render thread only.
    static void useReadableFont(vtkChartXY* chart);
    // The legend of a 2D chart sits outside the axes' box, never over the
    // curves: at the right (short labels) or below (long ones).
    enum class LegendPlace { Right, Below };
    // A 2D chart drawn in this plot's window: `view` renders into it on a
    // white background and shows `chart`, with readable axis numbers and its
    // legend outside the data. Render thread only.
    void showChart(vtkContextView* view, vtkChartXY* chart, LegendPlace legend = LegendPlace::Right) const;
    static void placeLegend(vtkChartXY* chart, LegendPlace legend);
    // The left (value) axis: automatic and linear, or logarithmic over the
    // positive values' range [lo, hi], at most `decades` decades below hi.
    // Given its range explicitly, VTK's log axis never starts from a linear
    // range that spans 0 (on which it stays linear while the curves are
    // drawn in log10: the in-plane plot went blank). Render thread only.
    static void setValueAxis(vtkChartXY* chart, bool log_scale, double lo, double hi, double decades = 4.0);
    // DejaVu Sans for text that needs more than Latin letters (the "π" of
    // "πf"); the built-in font stays if the file is missing. Render thread only.
    static void useUnicodeFont(vtkTextProperty* text);
    // Called on the render thread before each drawing, at its size in pixels:
    // charts whose layout depends on the size (a*b*'s equal scales) set it here.
    virtual void layoutForSize(int /*width_px*/, int /*height_px*/) {}
    static QString csvText(const QString& text);

private:
    struct Gl;         // render-thread objects: context, framebuffer, VTK window
    QImage drawNow();  // render thread
    void showImage(const QImage& image);
    QSize devicePixels() const;
    void noteSize();  // GUI thread: the size the next drawing has

    QOffscreenSurface* m_surface = nullptr;  // created and destroyed on the GUI thread, as Qt requires
    std::unique_ptr<Gl> m_gl;
    QImage m_image;  // the latest drawing, shown by paintEvent
    std::atomic<int> m_width_px{0};
    std::atomic<int> m_height_px{0};
    std::atomic<double> m_pixel_ratio{1.0};
    std::atomic<bool> m_render_queued{false};
    std::atomic<double> m_paint_ms{0.0};
    double m_show_ms = 0.0;
    bool m_dirty_while_hidden = false;
    QString m_failure;  // set once, in the constructor
};

}  // namespace paintlab::gui
