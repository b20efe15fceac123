#pragma once
// Spectra against wavelength: the paint's reflectance factor at the six
// multi-angle geometries (setBrdf), or any list of named spectra, such as the
// optical data of the ingredients a recipe is made of (setSpectra with
// recipeSpectra, plot_data.h). Spectra of different quantities (an absorption
// coefficient, a refractive index) are not drawn on one axis: the plot shows
// one quantity at a time (setQuantity), the first by default.

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

    const std::vector<NamedSpectrum>& spectra() const { return m_spectra; }
    // Those of the shown quantity, as drawn.
    std::vector<NamedSpectrum> shownSpectra() const;
    // The shown spectra: columns series,quantity,wavelength_nm,value (one row per sample).
    bool exportCsv(const QString& path) const override;

signals:
    void quantitiesChanged();

private:
    void updateChart();
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;  // render thread only (plot_widget.h)
    std::vector<NamedSpectrum> m_spectra;
    std::string m_quantity;
    QString m_title;
};

}  // namespace paintlab::gui
