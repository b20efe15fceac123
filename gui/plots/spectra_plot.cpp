#include "spectra_plot.h"

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/multiangle.h"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <algorithm>
#include <array>

namespace paintlab::gui {

struct SpectraPlot::Vtk {
    vtkNew<vtkContextView> view;
    vtkNew<vtkChartXY> chart;
    std::vector<vtkSmartPointer<vtkTable>> tables;  // one per shown spectrum: grids differ
};

namespace {

// Colour-blind-safe qualitative palette (Okabe & Ito 2008) plus greys.
constexpr std::array<std::array<unsigned char, 3>, 9> kPalette{{{0, 114, 178},
                                                                {213, 94, 0},
                                                                {0, 158, 115},
                                                                {204, 121, 167},
                                                                {86, 180, 233},
                                                                {230, 159, 0},
                                                                {0, 0, 0},
                                                                {120, 120, 120},
                                                                {240, 228, 66}}};

}  // namespace

SpectraPlot::SpectraPlot(QWidget* parent) : PlotWidget(parent) {
    runOnRenderThread([this] {
        m_vtk = std::make_unique<Vtk>();
        showChart(m_vtk->view, m_vtk->chart);
        m_vtk->chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("wavelength (nm)");
        m_vtk->chart->SetShowLegend(true);
    });
    updateChart();
}

SpectraPlot::~SpectraPlot() {
    runOnRenderThread([this] { m_vtk.reset(); });
}

void SpectraPlot::setBrdf(const SpectralBrdf& brdf) {
    setSpectra(multiAngleSpectra(multiAngleColours(brdf), brdf.wavelengthsNm()),
               tr("Paint reflectance factor at the multi-angle geometries"));
}

void SpectraPlot::setSpectra(std::vector<NamedSpectrum> spectra, const QString& title) {
    const std::vector<std::string> before = quantities();
    m_spectra = std::move(spectra);
    m_title = title;
    const std::vector<std::string> now = quantities();
    if (std::find(now.begin(), now.end(), m_quantity) == now.end())
        m_quantity = now.empty() ? std::string() : now.front();
    updateChart();
    if (now != before) emit quantitiesChanged();
}

std::vector<std::string> SpectraPlot::quantities() const {
    std::vector<std::string> out;
    for (const NamedSpectrum& s : m_spectra)
        if (std::find(out.begin(), out.end(), s.quantity) == out.end()) out.push_back(s.quantity);
    return out;
}

void SpectraPlot::setQuantity(const std::string& quantity) {
    m_quantity = quantity;
    updateChart();
}

std::vector<NamedSpectrum> SpectraPlot::shownSpectra() const {
    std::vector<NamedSpectrum> out;
    for (const NamedSpectrum& s : m_spectra)
        if (s.quantity == m_quantity) out.push_back(s);
    return out;
}

void SpectraPlot::updateChart() {
    // The render thread draws copies: the GUI thread may change the spectra meanwhile.
    onRenderThread([this, shown = shownSpectra(), title = m_title.toStdString(), quantity = m_quantity] {
        vtkChartXY* chart = m_vtk->chart;
        chart->ClearPlots();
        m_vtk->tables.clear();
        chart->SetTitle(title);
        chart->GetAxis(vtkAxis::LEFT)->SetTitle(quantity);
        for (std::size_t k = 0; k < shown.size(); ++k) {
            const Spectrum& s = shown[k].spectrum;
            auto table = vtkSmartPointer<vtkTable>::New();
            vtkNew<vtkDoubleArray> wavelength;
            wavelength->SetName("wavelength_nm");
            table->AddColumn(wavelength);
            vtkNew<vtkDoubleArray> value;
            value->SetName(shown[k].name.c_str());
            table->AddColumn(value);
            // A constant spectrum (one sample) is drawn across the visible range.
            const std::vector<double> nm =
                s.isConstant() ? std::vector<double>{kVisibleMinNm, kVisibleMaxNm} : s.wavelengthsNm();
            table->SetNumberOfRows(static_cast<vtkIdType>(nm.size()));
            for (std::size_t i = 0; i < nm.size(); ++i) {
                table->SetValue(static_cast<vtkIdType>(i), 0, nm[i]);
                table->SetValue(static_cast<vtkIdType>(i), 1, s(nm[i]));
            }
            vtkPlot* line = chart->AddPlot(vtkChart::LINE);
            line->SetInputData(table, 0, 1);
            const auto& c = kPalette[k % kPalette.size()];
            line->SetColor(c[0], c[1], c[2], 255);
            line->SetWidth(2.0F);
            m_vtk->tables.push_back(table);
        }
    });
    emit dataChanged();
}

bool SpectraPlot::exportCsv(const QString& path) const {
    std::vector<QStringList> rows;
    for (const NamedSpectrum& s : shownSpectra()) {
        const QString name = csvText(QString::fromStdString(s.name));
        const QString quantity = csvText(QString::fromStdString(s.quantity));
        const std::vector<double>& nm = s.spectrum.wavelengthsNm();
        for (std::size_t i = 0; i < s.spectrum.values().size(); ++i)
            rows.push_back({name, quantity, s.spectrum.isConstant() ? QString() : csvNumber(nm[i]),
                            csvNumber(s.spectrum.values()[i])});
    }
    return writeCsv(path, {"series", "quantity", "wavelength_nm", "value"}, rows);
}

}  // namespace paintlab::gui
