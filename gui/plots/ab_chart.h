#pragma once
// CIELAB a*b* chart of the paint's colours at the six multi-angle geometries
// (45as-15 .. 45as110, D65 / 10°, engine multiangle.h): each point drawn in
// its own colour and labelled with its geometry, joined in aspecular order
// (the flop path from the near-specular to the flop angle); optionally a
// second BRDF's path dashed. Both axes span the same range over a square box
// of axes, so the chroma and hue of the path are not distorted, whatever the
// widget's shape; labels are placed where they overlap no other.

#include "plot_widget.h"

#include "paintlab/engine/multiangle.h"

#include <QRectF>

#include <memory>
#include <vector>

namespace paintlab {
class SpectralBrdf;
}

namespace paintlab::gui {

class AbChart : public PlotWidget {
    Q_OBJECT
public:
    explicit AbChart(QWidget* parent = nullptr);
    ~AbChart() override;
    AbChart(const AbChart&) = delete;
    AbChart& operator=(const AbChart&) = delete;
    AbChart(AbChart&&) = delete;
    AbChart& operator=(AbChart&&) = delete;

    // multiAngleColours of the BRDF (six evaluations) and a redraw.
    void setBrdf(const SpectralBrdf& brdf);
    void setReport(MultiAngleReport report);
    void setComparison(const SpectralBrdf& brdf, const QString& label);
    void setComparisonReport(MultiAngleReport report, const QString& label);
    void clearComparison();
    bool hasComparison() const { return !m_comparison.colours.empty(); }

    const MultiAngleReport& report() const { return m_report; }
    const MultiAngleReport& comparisonReport() const { return m_comparison; }
    // The aspecular angles of the drawn path, read back from the chart's own
    // table, in the order its points are joined.
    std::vector<double> pathAspecularDeg() const;
    // Where the geometry labels were drawn last (pixels, y up), in report order.
    std::vector<QRectF> labelRects() const;
    // Columns series,aspecular_deg,L,a,b,X,Y,Z; series "current" or the comparison's label.
    bool exportCsv(const QString& path) const override;

protected:
    // The axes' box is made square (both axes span the same range): one unit
    // of a* is as long as one of b*, as a colour-difference chart needs.
    void layoutForSize(int width_px, int height_px) override;

private:
    void updateChart();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;  // render thread only (plot_widget.h)
    MultiAngleReport m_report;
    MultiAngleReport m_comparison;
    QString m_comparison_label;
};

}  // namespace paintlab::gui
