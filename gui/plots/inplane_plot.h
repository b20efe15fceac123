#pragma once
// In-plane reflectance factor of the paint (pi f, linear sRGB channels and
// CIE Y) against the viewing angle for light from 45 degrees, drawn by VTK's
// chart classes into a Qt6 QOpenGLWidget through vtkGenericOpenGLRenderWindow
// (shared/notes/debian12-stack.md, trap 1: initializeGL makes the VTK window
// ready and current and initialises its context; resizeGL sizes it; paintGL
// renders and VTK blits into the widget's framebuffer). No VTK type leaks
// out of this header.

#include <QOpenGLWidget>

#include <memory>
#include <vector>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

class InplanePlot : public QOpenGLWidget {
    Q_OBJECT
public:
    explicit InplanePlot(QWidget* parent = nullptr);
    ~InplanePlot() override;
    InplanePlot(const InplanePlot&) = delete;
    InplanePlot& operator=(const InplanePlot&) = delete;
    InplanePlot(InplanePlot&&) = delete;
    InplanePlot& operator=(InplanePlot&&) = delete;

    // Recomputes the curves from the BRDF (a few milliseconds) and redraws.
    void setBrdf(const LayeredBrdf& brdf);
    void setLogScale(bool log_scale);

    // The plotted data: view angle (deg, negative = towards the light) and per
    // angle R, G, B, Y reflectance factors.
    struct Curve {
        std::vector<double> view_deg;
        std::vector<double> r, g, b, y;
    };
    const Curve& curve() const { return m_curve; }
    // Writes the curve as CSV; returns false (and nothing is half written) on failure.
    bool exportCsv(const QString& path) const;

protected:
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;

private:
    void updateChart();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;
    Curve m_curve;
    bool m_log_scale = false;
};

}  // namespace paintlab::gui
