#pragma once
// Spectra against wavelength: the paint's reflectance factor at the six
// multi-angle geometries (setBrdf), or any list of named spectra, such as the
// optical data of the ingredients a recipe is made of (setSpectra with
// recipeSpectra, plot_data.h). Spectra of different quantities (an absorption
// coefficient, a refractive index) are not drawn on one axis: the plot shows
// one quantity at a time (setQuantity), the first by default. A comparison
// is drawn dashed; the value axis can be logarithmic.

#include "plot_data.h"
#include "plot_widget.h"

#include <memory>
#include <string>
#include <vector>

namespace paintlab {
class SpectralBrdf;
}

namespace paintlab::gui {

class SpectraPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit SpectraPlot(QWidget* parent = nullptr);
    ~SpectraPlot() override;
    SpectraPlot(const SpectraPlot&) = delete;
    SpectraPlot& operator=(const SpectraPlot&) = delete;
    SpectraPlot(SpectraPlot&&) = delete;
    SpectraPlot& operator=(SpectraPlot&&) = delete;

    // The reflectance factor spectra at the multi-angle geometries (multiangle.h).
    void setBrdf(const SpectralBrdf& brdf);
    // Any spectra; the shown quantity stays if it is still among them.
    void setSpectra(std::vector<NamedSpectrum> spectra, const QString& title);
    // The distinct quantities, in the order they first appear.
    std::vector<std::string> quantities() const;
    void setQuantity(const std::string& quantity);
    const std::string& quantity() const { return m_quantity; }

    // A logarithmic value axis; values <= 0 are then not drawn (the title says so).
    void setLogScale(bool log_scale);
    bool logScale() const { return m_log_scale; }
    // Spectra of another BRDF (a pinned state, the full model) drawn dashed in
    // the colours of the current ones of the same name; clearComparison removes them.
    void setComparisonSpectra(std::vector<NamedSpectrum> spectra, const QString& label);
    void clearComparison();
    bool hasComparison() const { return !m_comparison.empty(); }
    const std::vector<NamedSpectrum>& comparisonSpectra() const { return m_comparison; }

    const std::vector<NamedSpectrum>& spectra() const { return m_spectra; }
    // Those of the shown quantity, as drawn.
    std::vector<NamedSpectrum> shownSpectra() const;
    // The shown spectra: columns series,quantity,wavelength_nm,value (one row
    // per sample); a comparison's series are named "<label>: <name>".
    bool exportCsv(const QString& path) const override;

signals:
    void quantitiesChanged();

private:
    void updateChart();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;  // render thread only (plot_widget.h)
    std::vector<NamedSpectrum> m_spectra;
    std::vector<NamedSpectrum> m_comparison;
    QString m_comparison_label;
    std::string m_quantity;
    QString m_title;
    bool m_log_scale = false;
};

}  // namespace paintlab::gui
