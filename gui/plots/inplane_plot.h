#pragma once
// In-plane reflectance factor of the paint (pi f) against the viewing angle,
// at several incidences: CIE Y per incidence and, for the 45 degree light, the
// linear sRGB channels; optionally a second BRDF (another version of the
// recipe, or the full model) overlaid with dashed lines. Linear or logarithmic
// axis. Drawn by VTK's chart classes (PlotWidget). No VTK type leaks out of
// this header.

#include "plot_data.h"
#include "plot_widget.h"

#include <memory>
#include <vector>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

class InplanePlot : public PlotWidget {
    Q_OBJECT
public:
    explicit InplanePlot(QWidget* parent = nullptr);
    ~InplanePlot() override;
    InplanePlot(const InplanePlot&) = delete;
    InplanePlot& operator=(const InplanePlot&) = delete;
    InplanePlot(InplanePlot&&) = delete;
    InplanePlot& operator=(InplanePlot&&) = delete;

    // Recomputes the curves from the BRDF (a few milliseconds, plot_data.h) and redraws.
    void setBrdf(const LayeredBrdf& brdf);
    // The same, keeping the BRDF so that setIncidences recomputes at once.
    void setBrdf(std::shared_ptr<const LayeredBrdf> brdf);
    void setLogScale(bool log_scale);
    bool logScale() const { return m_log_scale; }
    // The incidences drawn (degrees, each in [0, 90)); 45 is always kept, for
    // curve(). Default: 45 alone (the main window's central plot); the Plots
    // dock shows 15, 30, 45, 60, 75.
    void setIncidences(const std::vector<double>& incidences_deg);
    const std::vector<double>& incidences() const { return m_incidences; }
    // A second BRDF drawn dashed, labelled (e.g. "version 3", "full model");
    // clearComparison removes it.
    void setComparison(const LayeredBrdf& brdf, const QString& label);
    void clearComparison();
    bool hasComparison() const { return !m_comparison.empty(); }

    // Measured BRDF samples in the plane of the 45 degree curve (plot_data.h
    // inplaneSamples) drawn as points in the R, G, B colours, with
    // `label` (the measurement's name) in the legend and the title saying
    // how many of its samples lie in the plane; while they are shown the
    // comparison (the fitted recipe) is drawn with its R, G, B curves too.
    void setMeasuredSamples(InplaneSamples samples, const QString& label);
    void clearMeasuredSamples();
    bool hasMeasuredSamples() const { return !m_measured_label.isEmpty(); }
    const InplaneSamples& measuredSamples() const { return m_measured; }
    // The points drawn (the samples in the plane), and the title's line
    // that says so ("points: 45 of the 1768 samples of NAME lie within 2.5
    // deg of this plane"; empty without samples).
    std::size_t measuredPointsDrawn() const { return m_measured.view_deg.size(); }
    QString measuredCaption() const;

    // The plotted data at the 45 degree incidence (else the first curve's):
    // view angle (deg, negative = towards the light) and per angle R, G, B, Y
    // reflectance factors.
    using Curve = InplaneCurve;
    const Curve& curve() const { return m_curve; }
    // Curves computed elsewhere (plot_data.h inplaneCurves, on a worker
    // thread): only the chart is updated here. incidences() become theirs.
    void setCurves(std::vector<Curve> curves);
    void setComparisonCurves(std::vector<Curve> curves, const QString& label);
    // Every incidence, in incidences() order; and the comparison's (empty without one).
    const std::vector<Curve>& curves() const { return m_curves; }
    const std::vector<Curve>& comparisonCurves() const { return m_comparison; }
    // Columns series,theta_i_deg,view_deg,R,G,B,Y; series "current" or the comparison's label.
    bool exportCsv(const QString& path) const override;

protected:
    void layoutForSize(int width_px, int height_px) override;

private:
    void compute(const LayeredBrdf& brdf);
    void pickPrimary();
    void updateChart();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;  // render thread only (plot_widget.h)
    int m_laid_out_width = 0;    // render thread only: the size of the last layoutForSize
    int m_laid_out_height = 0;
    std::shared_ptr<const LayeredBrdf> m_brdf;
    std::vector<double> m_incidences{45.0};
    std::vector<Curve> m_curves;
    std::vector<Curve> m_comparison;
    QString m_comparison_label;
    InplaneSamples m_measured;
    QString m_measured_label;
    Curve m_curve;
    bool m_log_scale = false;
};

}  // namespace paintlab::gui
