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
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <algorithm>
#include <array>
#include <initializer_list>
#include <limits>

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

// Of the spectra, those of one quantity.
std::vector<NamedSpectrum> ofQuantity(const std::vector<NamedSpectrum>& spectra,
                                      const std::string& quantity) {
    std::vector<NamedSpectrum> out;
    for (const NamedSpectrum& s : spectra)
        if (s.quantity == quantity) out.push_back(s);
    return out;
}

// The value axis' title: the quantity if it is short enough to fit beside
// the axis, else its last word and unit ("coefficients (1/µm)"); the chart's
// title then names the quantity in full.
std::string axisTitleOf(const std::string& quantity) {
    constexpr std::size_t kFits = 28;  // characters beside a ~200-pixel axis
    const std::size_t unit = quantity.rfind(" (");
    if (quantity.size() <= kFits || unit == std::string::npos) return quantity;
    const std::size_t word = quantity.rfind(' ', unit - 1);
    return quantity.substr(word == std::string::npos ? 0 : word + 1);
}

// A table of one spectrum over wavelength; a constant one across the visible
// range. On a log axis values <= 0 become NaN (not drawn); `dropped` is then set.
vtkSmartPointer<vtkTable> spectrumTable(const NamedSpectrum& named, bool log_scale, bool& dropped) {
    const Spectrum& s = named.spectrum;
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> wavelength;
    wavelength->SetName("wavelength_nm");
    table->AddColumn(wavelength);
    vtkNew<vtkDoubleArray> value;
    value->SetName(named.name.c_str());
    table->AddColumn(value);
    const std::vector<double> nm =
        s.isConstant() ? std::vector<double>{kVisibleMinNm, kVisibleMaxNm} : s.wavelengthsNm();
    table->SetNumberOfRows(static_cast<vtkIdType>(nm.size()));
    for (std::size_t i = 0; i < nm.size(); ++i) {
        double v = s(nm[i]);
        if (log_scale && !(v > 0.0)) {
            v = std::numeric_limits<double>::quiet_NaN();
            dropped = true;
        }
        table->SetValue(static_cast<vtkIdType>(i), 0, nm[i]);
        table->SetValue(static_cast<vtkIdType>(i), 1, v);
    }
    return table;
}

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

std::vector<NamedSpectrum> SpectraPlot::shownSpectra() const { return ofQuantity(m_spectra, m_quantity); }

void SpectraPlot::setLogScale(bool log_scale) {
    m_log_scale = log_scale;
    updateChart();
}

void SpectraPlot::setComparisonSpectra(std::vector<NamedSpectrum> spectra, const QString& label) {
    m_comparison = std::move(spectra);
    m_comparison_label = label.isEmpty() ? QStringLiteral("comparison") : label;
    updateChart();
}

void SpectraPlot::clearComparison() {
    m_comparison.clear();
    m_comparison_label.clear();
    updateChart();
}

void SpectraPlot::updateChart() {
    QStringList lines{m_title};
    const std::string axis_title = axisTitleOf(m_quantity);
    if (axis_title != m_quantity) lines << QString::fromStdString(m_quantity);
    const std::vector<NamedSpectrum> compared = ofQuantity(m_comparison, m_quantity);
    if (!compared.empty()) lines << tr("dashed: %1").arg(m_comparison_label);
    // The render thread draws copies: the GUI thread may change the spectra meanwhile.
    onRenderThread(
        [this, shown = shownSpectra(), compared, lines, axis_title, log_scale = m_log_scale,
         short_label = m_comparison_label.section(QStringLiteral(" ("), 0, 0).toStdString()]() mutable {
            vtkChartXY* chart = m_vtk->chart;
            chart->ClearPlots();
            m_vtk->tables.clear();
            chart->GetAxis(vtkAxis::LEFT)->SetTitle(axis_title);
            bool dropped = false;
            const auto add = [&](const NamedSpectrum& s, std::size_t colour) {
                vtkSmartPointer<vtkTable> table = spectrumTable(s, log_scale, dropped);
                vtkPlot* line = chart->AddPlot(vtkChart::LINE);
                line->SetInputData(table, 0, 1);
                const auto& c = kPalette[colour % kPalette.size()];
                line->SetColor(c[0], c[1], c[2], 255);
                line->SetWidth(2.0F);
                m_vtk->tables.push_back(table);
                return line;
            };
            // Long names (the ingredients' "layer > component > field") go below the axes.
            const bool long_names = std::any_of(shown.begin(), shown.end(),
                                                [](const NamedSpectrum& s) { return s.name.size() > 20; });
            placeLegend(chart, long_names ? LegendPlace::Below : LegendPlace::Right);
            for (std::size_t k = 0; k < shown.size(); ++k) add(shown[k], k)->SetLabel(shown[k].name);
            for (std::size_t k = 0; k < compared.size(); ++k) {
                // The colour of the current spectrum of the same name; one legend line for them all.
                const auto same = std::find_if(shown.begin(), shown.end(), [&](const NamedSpectrum& s) {
                    return s.name == compared[k].name;
                });
                vtkPlot* line = add(compared[k], static_cast<std::size_t>(same - shown.begin()) +
                                                     (same == shown.end() ? k : 0));
                line->GetPen()->SetLineType(vtkPen::DASH_LINE);
                line->SetLabel("dashed: " + short_label);
                line->SetLegendVisibility(k == 0);
            }
            if (dropped) lines << QStringLiteral("log axis: values <= 0 are not drawn");
            chart->SetTitle(lines.join(QLatin1Char('\n')).toStdString());
            double lo = std::numeric_limits<double>::infinity();
            double hi = 0.0;
            for (const std::vector<NamedSpectrum>* set :
                 std::initializer_list<const std::vector<NamedSpectrum>*>{&shown, &compared})
                for (const NamedSpectrum& s : *set)
                    for (double v : s.spectrum.values())
                        if (v > 0.0) {
                            lo = std::min(lo, v);
                            hi = std::max(hi, v);
                        }
            chart->RecalculateBounds();
            setValueAxis(chart, log_scale, lo, hi);
        });
    emit dataChanged();
}

bool SpectraPlot::exportCsv(const QString& path) const {
    std::vector<QStringList> rows;
    const auto add = [&rows](const std::vector<NamedSpectrum>& spectra, const QString& prefix) {
        for (const NamedSpectrum& s : spectra) {
            const QString name = csvText(prefix + QString::fromStdString(s.name));
            const QString quantity = csvText(QString::fromStdString(s.quantity));
            const std::vector<double>& nm = s.spectrum.wavelengthsNm();
            for (std::size_t i = 0; i < s.spectrum.values().size(); ++i)
                rows.push_back({name, quantity, s.spectrum.isConstant() ? QString() : csvNumber(nm[i]),
                                csvNumber(s.spectrum.values()[i])});
        }
    };
    add(shownSpectra(), QString());
    add(ofQuantity(m_comparison, m_quantity), m_comparison_label + QStringLiteral(": "));
    return writeCsv(path, {"series", "quantity", "wavelength_nm", "value"}, rows);
}

}  // namespace paintlab::gui
