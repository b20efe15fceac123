#include "inplane_plot.h"

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

namespace paintlab::gui {

struct InplanePlot::Vtk {
    vtkNew<vtkContextView> view;
    vtkNew<vtkChartXY> chart;
    vtkNew<vtkTable> table;       // view_deg, then the current BRDF's columns
    vtkNew<vtkTable> comparison;  // the same for the comparison
    vtkNew<vtkTable> measured;    // view_deg, R, G, B of the measured samples in the plane
};

namespace {

constexpr double kPrimaryIncidenceDeg = 45.0;

// Y per incidence: a distinct colour each, the 45 degree light (the primary curve) black.
std::array<unsigned char, 3> incidenceColour(std::size_t k, std::size_t count) {
    static constexpr std::array<std::array<unsigned char, 3>, 6> kPalette{
        {{90, 40, 160}, {30, 90, 200}, {20, 20, 20}, {220, 120, 20}, {150, 70, 30}, {0, 140, 140}}};
    if (count == 1) return kPalette[2];
    return kPalette[k % kPalette.size()];
}

// R, G, B of the primary curve, the comparison's dashed ones and the measured points.
constexpr unsigned char kChannelColour[3][3] = {{200, 30, 30}, {30, 150, 30}, {30, 60, 200}};

QString degrees(double v) { return QString::number(v, 'g', 4) + QStringLiteral(" deg"); }

// What a value is drawn as. Linear sRGB channels below zero are colours
// outside the sRGB gamut (the spectral BRDF itself is never negative): drawn
// at zero, and their legend says so. A log axis cannot show zero or less:
// such points are not drawn (NaN breaks the line) and the title says so.
double shown(double v, bool log_scale, bool clip_at_zero) {
    if (log_scale && !(v > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return clip_at_zero ? std::max(v, 0.0) : v;
}

bool anyNonPositive(const std::vector<double>& values) {
    return std::any_of(values.begin(), values.end(), [](double v) { return !(v > 0.0); });
}

bool anyNegative(const std::vector<double>& values) {
    return std::any_of(values.begin(), values.end(), [](double v) { return v < 0.0; });
}

// Fills a table: column 0 the view angle, then Y per curve, then R, G, B of
// the curve at `primary` (clipped at zero; see shown()).
void fillTable(vtkTable* t, const std::vector<InplaneCurve>& curves, std::size_t primary, bool log_scale) {
    t->Initialize();
    const auto addColumn = [t](const char* name) {
        vtkNew<vtkDoubleArray> column;
        column->SetName(name);
        t->AddColumn(column);
    };
    addColumn("view_deg");
    for (std::size_t k = 0; k < curves.size(); ++k)
        addColumn(QStringLiteral("Y%1").arg(k).toUtf8().constData());
    const bool channels = primary < curves.size();
    if (channels)
        for (const char* ch : {"R", "G", "B"}) addColumn(ch);
    if (curves.empty()) return;
    const auto n = static_cast<vtkIdType>(curves.front().view_deg.size());
    t->SetNumberOfRows(n);
    for (vtkIdType i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        t->SetValue(i, 0, curves.front().view_deg[k]);
        vtkIdType col = 1;
        for (const InplaneCurve& c : curves) t->SetValue(i, col++, shown(c.y[k], log_scale, false));
        if (channels) {
            const InplaneCurve& p = curves[primary];
            t->SetValue(i, col++, shown(p.r[k], log_scale, true));
            t->SetValue(i, col++, shown(p.g[k], log_scale, true));
            t->SetValue(i, col++, shown(p.b[k], log_scale, true));
        }
    }
    t->Modified();
}

// The measured points: view angle, then pi f in R, G, B (log axis: values <= 0 left out).
void fillMeasuredTable(vtkTable* t, const InplaneSamples& samples, bool log_scale) {
    t->Initialize();
    for (const char* name : {"view_deg", "R", "G", "B"}) {
        vtkNew<vtkDoubleArray> column;
        column->SetName(name);
        t->AddColumn(column);
    }
    const auto n = static_cast<vtkIdType>(samples.view_deg.size());
    t->SetNumberOfRows(n);
    for (vtkIdType i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        t->SetValue(i, 0, samples.view_deg[k]);
        t->SetValue(i, 1, shown(samples.r[k], log_scale, false));
        t->SetValue(i, 2, shown(samples.g[k], log_scale, false));
        t->SetValue(i, 3, shown(samples.b[k], log_scale, false));
    }
    t->Modified();
}

// The smallest positive and the largest value of the tables' value columns
// (all but the first), as drawn.
std::pair<double, double> positiveRange(std::initializer_list<vtkTable*> tables) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = 0.0;
    for (vtkTable* t : tables)
        for (vtkIdType col = 1; col < t->GetNumberOfColumns(); ++col)
            for (vtkIdType row = 0; row < t->GetNumberOfRows(); ++row) {
                const double v = t->GetValue(row, col).ToDouble();
                if (v > 0.0) {
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
            }
    return {lo, hi};
}

// The legend of one channel of the primary curve, marked "*" if it goes
// below zero; `notes` gets the line of the title that explains the mark.
std::string channelLabel(const char* channel, const std::vector<double>& values, double theta_i_deg,
                         QStringList& notes) {
    const bool negative = anyNegative(values);
    if (negative)
        notes << QStringLiteral("*%1 < 0 (to %2): outside the sRGB gamut,")
                     .arg(channel)
                     .arg(*std::min_element(values.begin(), values.end()), 0, 'f', 3)
              << QStringLiteral("its spectrum is positive: drawn at 0");
    return QStringLiteral("%1%2 (linear sRGB, %3)")
        .arg(channel, negative ? QStringLiteral("*") : QString(), degrees(theta_i_deg))
        .toStdString();
}

}  // namespace

InplanePlot::InplanePlot(QWidget* parent) : PlotWidget(parent) {
    runOnRenderThread([this] {
        m_vtk = std::make_unique<Vtk>();
        showChart(m_vtk->view, m_vtk->chart);
        m_vtk->chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("view angle (deg, negative: light side)");
        vtkAxis* left = m_vtk->chart->GetAxis(vtkAxis::LEFT);
        left->SetTitle("reflectance factor \u03c0f");  // pi f: 1 for a white diffuser
        useUnicodeFont(left->GetTitleProperties());
        m_vtk->chart->SetShowLegend(true);
    });
    updateChart();
}

InplanePlot::~InplanePlot() {
    runOnRenderThread([this] { m_vtk.reset(); });
}

void InplanePlot::compute(const LayeredBrdf& brdf) {
    m_curves = inplaneCurves(brdf, m_incidences);
    pickPrimary();
}

void InplanePlot::pickPrimary() {
    const auto primary = std::find_if(m_curves.begin(), m_curves.end(),
                                      [](const Curve& c) { return c.theta_i_deg == kPrimaryIncidenceDeg; });
    m_curve = primary != m_curves.end() ? *primary : m_curves.empty() ? Curve{} : m_curves.front();
}

void InplanePlot::setCurves(std::vector<Curve> curves) {
    m_brdf.reset();
    m_curves = std::move(curves);
    m_incidences.clear();
    for (const Curve& c : m_curves) m_incidences.push_back(c.theta_i_deg);
    pickPrimary();
    updateChart();
}

void InplanePlot::setComparisonCurves(std::vector<Curve> curves, const QString& label) {
    m_comparison = std::move(curves);
    m_comparison_label = label.isEmpty() ? QStringLiteral("comparison") : label;
    updateChart();
}

void InplanePlot::setMeasuredSamples(InplaneSamples samples, const QString& label) {
    m_measured = std::move(samples);
    m_measured_label = label.isEmpty() ? QStringLiteral("measured") : label;
    updateChart();
}

void InplanePlot::clearMeasuredSamples() {
    m_measured = {};
    m_measured_label.clear();
    updateChart();
}

QString InplanePlot::measuredCaption() const {
    if (!hasMeasuredSamples()) return {};
    return QStringLiteral("points: %1 of the %2 samples of %3 lie within %4 of this plane")
        .arg(m_measured.view_deg.size())
        .arg(m_measured.total)
        .arg(m_measured_label)
        .arg(degrees(m_measured.tolerance_deg));
}

void InplanePlot::setBrdf(const LayeredBrdf& brdf) {
    m_brdf.reset();
    compute(brdf);
    updateChart();
}

void InplanePlot::setBrdf(std::shared_ptr<const LayeredBrdf> brdf) {
    m_brdf = std::move(brdf);
    if (m_brdf) compute(*m_brdf);
    updateChart();
}

void InplanePlot::setLogScale(bool log_scale) {
    m_log_scale = log_scale;
    updateChart();
}

void InplanePlot::setIncidences(const std::vector<double>& incidences_deg) {
    std::vector<double> kept;
    for (double t : incidences_deg)
        if (t >= 0.0 && t < 90.0 && std::find(kept.begin(), kept.end(), t) == kept.end()) kept.push_back(t);
    if (std::find(kept.begin(), kept.end(), kPrimaryIncidenceDeg) == kept.end())
        kept.push_back(kPrimaryIncidenceDeg);
    std::sort(kept.begin(), kept.end());
    m_incidences = std::move(kept);
    if (m_brdf) compute(*m_brdf);
    // The comparison is kept as computed: it is redone with its BRDF by setComparison.
    updateChart();
}

void InplanePlot::setComparison(const LayeredBrdf& brdf, const QString& label) {
    setComparisonCurves(inplaneCurves(brdf, m_incidences), label);
}

void InplanePlot::clearComparison() {
    m_comparison.clear();
    m_comparison_label.clear();
    updateChart();
}

void InplanePlot::updateChart() {
    // The R, G, B channels are drawn for the primary curve (curve()).
    const auto primary = static_cast<std::size_t>(
        std::find_if(m_curves.begin(), m_curves.end(),
                     [this](const Curve& c) { return c.theta_i_deg == m_curve.theta_i_deg; }) -
        m_curves.begin());
    QStringList lines{
        m_curves.size() == 1
            ? QStringLiteral("In-plane reflectance factor, light at %1").arg(degrees(m_curve.theta_i_deg))
            : QStringLiteral("In-plane reflectance factor at several incidences")};
    if (!m_comparison.empty()) lines << QStringLiteral("dashed: %1").arg(m_comparison_label);
    const bool points = hasMeasuredSamples();
    if (points) lines << measuredCaption();
    // With measured points the comparison (the fitted recipe) shows its
    // channels too, at the points' incidence.
    const auto comparison_primary = static_cast<std::size_t>(
        std::find_if(m_comparison.begin(), m_comparison.end(),
                     [this](const Curve& c) { return c.theta_i_deg == m_measured.theta_i_deg; }) -
        m_comparison.begin());
    const std::size_t comparison_channels = points ? comparison_primary : m_comparison.size();
    std::vector<std::string> channel_labels;
    if (primary < m_curves.size()) {
        const Curve& p = m_curves[primary];
        channel_labels = {channelLabel("R", p.r, p.theta_i_deg, lines),
                          channelLabel("G", p.g, p.theta_i_deg, lines),
                          channelLabel("B", p.b, p.theta_i_deg, lines)};
    }
    if (m_log_scale) {
        bool dropped = false;
        for (const std::vector<Curve>* set : {&m_curves, &m_comparison})
            for (const Curve& c : *set) dropped = dropped || anyNonPositive(c.y);
        if (primary < m_curves.size())
            for (const std::vector<double>* v : {&m_curve.r, &m_curve.g, &m_curve.b})
                dropped = dropped || anyNonPositive(*v);
        for (const std::vector<double>* v : {&m_measured.r, &m_measured.g, &m_measured.b})
            dropped = dropped || anyNonPositive(*v);
        if (dropped) lines << QStringLiteral("log axis: values <= 0 are not drawn");
    }
    const QString title = lines.join(QLatin1Char('\n'));
    // The comparison's legend line names it short: "full model", "version 3".
    const QString short_label = m_comparison_label.section(QStringLiteral(" ("), 0, 0);
    // The render thread draws copies: the GUI thread may change the curves meanwhile.
    const std::string points_label = m_measured_label.toStdString();
    const std::string points_at = degrees(m_measured.theta_i_deg).toStdString();
    onRenderThread([this, curves = m_curves, comparison = m_comparison, primary, title = title.toStdString(),
                    log_scale = m_log_scale, channel_labels, comparison_label = short_label.toStdString(),
                    comparison_channels, measured = points ? m_measured : InplaneSamples{}, points,
                    points_label, points_at] {
        fillTable(m_vtk->table, curves, primary, log_scale);
        fillTable(m_vtk->comparison, comparison, comparison_channels, log_scale);
        fillMeasuredTable(m_vtk->measured, measured, log_scale);
        vtkChartXY* chart = m_vtk->chart;
        chart->ClearPlots();
        chart->SetTitle(title);
        const auto addLines = [&](vtkTable* t, const std::vector<Curve>& drawn, bool dashed, bool channels) {
            if (drawn.empty()) return;
            vtkIdType col = 1;
            for (std::size_t k = 0; k < drawn.size(); ++k) {
                vtkPlot* line = chart->AddPlot(vtkChart::LINE);
                line->SetInputData(t, 0, col++);
                const auto c = incidenceColour(k, drawn.size());
                line->SetColor(c[0], c[1], c[2], 255);
                line->SetWidth(drawn[k].theta_i_deg == kPrimaryIncidenceDeg ? 2.5F : 1.8F);
                if (dashed) {
                    // One legend line for the whole comparison: its curves have the current ones' colours.
                    line->GetPen()->SetLineType(vtkPen::DASH_LINE);
                    line->SetLabel("dashed: " + comparison_label);
                    line->SetLegendVisibility(k == 0);
                } else {
                    line->SetLabel("Y, light at " + degrees(drawn[k].theta_i_deg).toStdString());
                }
            }
            if (!channels) return;
            for (std::size_t k = 0; k < 3; ++k) {
                vtkPlot* line = chart->AddPlot(vtkChart::LINE);
                line->SetInputData(t, 0, col++);
                line->SetColor(kChannelColour[k][0], kChannelColour[k][1], kChannelColour[k][2], 255);
                line->SetWidth(dashed ? 1.8F : 1.2F);
                if (dashed) {
                    line->GetPen()->SetLineType(vtkPen::DASH_LINE);
                    line->SetLegendVisibility(false);  // the comparison's one legend line above
                } else {
                    line->SetLabel(channel_labels[k]);
                }
            }
        };
        addLines(m_vtk->table, curves, false, true);
        addLines(m_vtk->comparison, comparison, true, points && comparison_channels < comparison.size());
        // The measured samples as markers, in the channels' colours.
        if (points)
            for (vtkIdType k = 0; k < 3; ++k) {
                vtkPlot* plot = chart->AddPlot(vtkChart::POINTS);
                plot->SetInputData(m_vtk->measured, 0, k + 1);
                const auto c = static_cast<std::size_t>(k);
                plot->SetColor(kChannelColour[c][0], kChannelColour[c][1], kChannelColour[c][2], 255);
                std::string label = k == 0 ? "R" : k == 1 ? "G" : "B";
                label += " measured (";
                label += points_label;
                label += ", light at ";
                label += points_at;
                label += ")";
                plot->SetLabel(label);
                if (auto* p = vtkPlotPoints::SafeDownCast(plot)) {
                    p->SetMarkerStyle(vtkPlotPoints::CIRCLE);
                    p->SetMarkerSize(7.0F);
                }
            }
        const auto [lo, hi] = positiveRange({m_vtk->table, m_vtk->comparison, m_vtk->measured});
        chart->RecalculateBounds();
        setValueAxis(chart, log_scale, lo, hi);
    });
    emit dataChanged();
}

void InplanePlot::layoutForSize(int width_px, int height_px) {
    if (!m_vtk) return;
    // A narrow plot (the main window's central one) keeps its width for the
    // curves: the legend goes below them.
    constexpr int kNarrowPx = 640;  // device pixels
    placeLegend(m_vtk->chart, width_px < kNarrowPx ? LegendPlace::Below : LegendPlace::Right);
    // Data handed over while the plot was hidden set the axes up for a
    // 1-pixel chart; at the first drawing at a real size the value axis
    // stayed empty (seen on the In-plane BRDF dock with measured points and
    // a tall legend). The bounds are recomputed whenever the size changes.
    if (width_px != m_laid_out_width || height_px != m_laid_out_height) {
        m_laid_out_width = width_px;
        m_laid_out_height = height_px;
        m_vtk->chart->RecalculateBounds();
    }
}

bool InplanePlot::exportCsv(const QString& path) const {
    std::vector<QStringList> rows;
    const auto add = [&rows](const std::vector<Curve>& curves, const QString& series) {
        for (const Curve& c : curves)
            for (std::size_t i = 0; i < c.view_deg.size(); ++i)
                rows.push_back({csvText(series), csvNumber(c.theta_i_deg), csvNumber(c.view_deg[i]),
                                csvNumber(c.r[i]), csvNumber(c.g[i]), csvNumber(c.b[i]), csvNumber(c.y[i])});
    };
    add(m_curves, QStringLiteral("current"));
    add(m_comparison, m_comparison_label);
    // The measured points: one row each, Y left empty (not measured).
    for (std::size_t i = 0; i < m_measured.view_deg.size(); ++i)
        rows.push_back({csvText(QStringLiteral("measured: ") + m_measured_label),
                        csvNumber(m_measured.theta_i_deg), csvNumber(m_measured.view_deg[i]),
                        csvNumber(m_measured.r[i]), csvNumber(m_measured.g[i]), csvNumber(m_measured.b[i]),
                        QString()});
    return writeCsv(path, {"series", "theta_i_deg", "view_deg", "R", "G", "B", "Y"}, rows);
}

}  // namespace paintlab::gui
