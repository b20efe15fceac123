#pragma once
// What every VTK plot of the workstation shares: VTK draws into a Qt6
// QOpenGLWidget through a vtkGenericOpenGLRenderWindow (Debian 12's VTK Qt
// module is Qt5-only, shared/notes/debian12-stack.md, trap 1). initializeGL
// makes the VTK window ready and current and initialises it from the widget's
// context; resizeGL sizes it; paintGL renders, and VTK blits into the
// framebuffer Qt has bound (the widget's, or grabFramebuffer's). Every plot
// exports what it shows as PNG and the numbers behind it as CSV.
//
// Only a forward declaration of the VTK window appears here, for subclasses;
// no VTK header is included.

#include <QOpenGLWidget>
#include <QString>
#include <QStringList>

#include <memory>
#include <vector>

class vtkChartXY;
class vtkGenericOpenGLRenderWindow;

namespace paintlab::gui {

class PlotWidget : public QOpenGLWidget {
    Q_OBJECT
public:
    explicit PlotWidget(QWidget* parent = nullptr);
    ~PlotWidget() override;
    PlotWidget(const PlotWidget&) = delete;
    PlotWidget& operator=(const PlotWidget&) = delete;
    PlotWidget(PlotWidget&&) = delete;
    PlotWidget& operator=(PlotWidget&&) = delete;

    // The plot as drawn, at the widget's size in device pixels; null if the
    // widget has never been shown (a QOpenGLWidget has no framebuffer before).
    QImage renderImage();
    // Writes renderImage() as PNG; false (and no file) if there is no image or
    // the file cannot be written.
    bool exportPng(const QString& path);
    // Writes the plotted numbers as CSV (full double precision); false (and
    // nothing half written) on failure.
    virtual bool exportCsv(const QString& path) const = 0;
    // GUI-thread time of the last paintGL (VTK's render and blit), ms.
    double lastPaintMs() const { return m_paint_ms; }

signals:
    // The plotted data changed (after setBrdf and the like).
    void dataChanged();

protected:
    vtkGenericOpenGLRenderWindow* renderWindow() const;
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;

    // One CSV file: a header line and rows of already formatted cells
    // (quoted where needed), atomically replaced (QSaveFile).
    static bool writeCsv(const QString& path, const QStringList& header,
                         const std::vector<QStringList>& rows);
    static QString csvNumber(double value);  // round-trips exactly
    // The chart's axis numbers in DejaVu Sans (Debian's fonts-dejavu-core)
    // instead of VTK's built-in Arial, whose zero is drawn like a "D" at
    // chart sizes ("D.1D" for 0.10); the built-in font stays if the file is
    // missing.
    static void useReadableFont(vtkChartXY* chart);
    static QString csvText(const QString& text);

private:
    // Gives VTK's GL objects back to the context that is about to go (initializeGL).
    void releaseGraphicsResources();

    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;
    double m_paint_ms = 0.0;
};

}  // namespace paintlab::gui
