#pragma once
// The BRDF lobe in 3D for one incidence (theta_i, phi_i): a surface over the
// outgoing hemisphere whose distance from the origin in direction wo is the
// luminance factor Y of pi f(wi, wo) (normalised to its maximum; optionally
// logarithmic over three decades), coloured at each direction by the hue and
// saturation of that reflectance factor's sRGB colour (plot_data.h
// displayColour: brightness is already the radius). The surface plane, the
// normal, the light's direction and its mirror direction are drawn for
// orientation. Drag with the left button to rotate (as VTK's trackball
// camera: azimuth and elevation about the focal point), the wheel or the right
// button to zoom, double-click to reset the view.
//
// The grid (46 rings x 96 azimuths, plot_data.h lobeGrid) is computed on the
// GUI thread from the Fourier coefficients of the BRDF: a few milliseconds
// (gui/README.md, "Plots").

#include "plot_data.h"
#include "plot_widget.h"

#include <array>
#include <memory>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

class LobePlot : public PlotWidget {
    Q_OBJECT
public:
    explicit LobePlot(QWidget* parent = nullptr);
    ~LobePlot() override;
    LobePlot(const LobePlot&) = delete;
    LobePlot& operator=(const LobePlot&) = delete;
    LobePlot(LobePlot&&) = delete;
    LobePlot& operator=(LobePlot&&) = delete;

    // Recomputes the lobe; the shared form keeps the BRDF, so that
    // setIncidence recomputes at once.
    void setBrdf(const LayeredBrdf& brdf);
    void setBrdf(std::shared_ptr<const LayeredBrdf> brdf);
    // A grid computed elsewhere (plot_data.h lobeGrid, on a worker thread):
    // only the VTK geometry is rebuilt here. The incidence becomes the grid's.
    void setGrid(LobeGrid grid);
    // theta_i in [0, 85], phi_i any (degrees). Recomputes if a BRDF is kept.
    void setIncidence(double theta_i_deg, double phi_i_deg);
    double thetaIDeg() const { return m_theta_i_deg; }
    double phiIDeg() const { return m_phi_i_deg; }
    void setLogRadius(bool log_radius);
    bool logRadius() const { return m_log_radius; }
    void resetView();

    const LobeGrid& grid() const { return m_grid; }
    // GUI-thread time of the last update (the grid, when computed here, and
    // copying it for the render thread, which builds the VTK geometry), ms.
    double lastUpdateMs() const { return m_update_ms; }
    std::array<double, 3> cameraPosition() const;
    // Columns theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,R,G,B,Y (linear sRGB
    // and Y of pi f), one row per grid direction.
    bool exportCsv(const QString& path) const override;

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;

private:
    void dolly(double factor);  // camera towards (> 1) or away from the focal point
    void compute(const LayeredBrdf& brdf);
    void updateScene();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;  // render thread only (plot_widget.h)
    std::shared_ptr<const LayeredBrdf> m_brdf;
    LobeGrid m_grid;
    double m_theta_i_deg = 45.0;
    double m_phi_i_deg = 0.0;
    bool m_log_radius = false;
    double m_update_ms = 0.0;
    QPoint m_last_mouse;
    Qt::MouseButton m_drag = Qt::NoButton;
};

}  // namespace paintlab::gui
