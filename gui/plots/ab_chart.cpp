#include "ab_chart.h"

#include "plot_data.h"

#include "paintlab/engine/brdf.h"

#include <QPointF>
#include <QSizeF>

#include <vtkAxis.h>
#include <vtkChart.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContext2D.h>
#include <vtkContextItem.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRect.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace paintlab::gui {

namespace {

// Text at data points, drawn over the chart in screen coordinates: each point
// is placed through the chart's axes (their screen ends and data range, as
// they were laid out for this frame). Drawn inside the chart's data transform
// instead, vtkContext2D strings did not appear (VTK 9.1).
class PointLabels : public vtkContextItem {
public:
    // As vtkStandardNewMacro (whose expansion ends without a semicolon, which
    // neither -Wpedantic with one nor clang-format without one accepts).
    static PointLabels* New() {
        auto* item = new PointLabels;
        item->InitializeObjectBase();
        return item;
    }

    vtkChartXY* chart = nullptr;
    std::vector<std::pair<double, double>> points;
    std::vector<std::string> labels;
    std::vector<QRectF> placed;  // where each label went in the last drawing

    bool Paint(vtkContext2D* painter) override {
        if (chart == nullptr) return false;
        vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
        vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
        const auto screen = [](vtkAxis* axis, double value, int k) {
            const double lo = axis->GetMinimum();
            const double hi = axis->GetMaximum();
            const auto p1 = static_cast<double>(axis->GetPosition1()[k]);
            const auto p2 = static_cast<double>(axis->GetPosition2()[k]);
            return hi > lo ? p1 + (value - lo) / (hi - lo) * (p2 - p1) : p1;
        };
        vtkTextProperty* text = painter->GetTextProp();
        text->SetColor(0.1, 0.1, 0.1);
        text->SetFontSize(13);
        text->SetBold(false);
        text->SetOrientation(0.0);  // the painter's text property is shared: an axis title left it at 90
        text->SetJustificationToLeft();
        text->SetVerticalJustificationToBottom();
        std::vector<QPointF> at;
        for (const auto& [a, b] : points) at.emplace_back(screen(x, a, 0), screen(y, b, 1));
        // Each label beside its point, at the first of eight places that
        // covers no label placed before and no other point (markers ~14 px).
        constexpr double kGap = 9.0;
        constexpr double kMarker = 8.0;
        placed.clear();
        for (std::size_t k = 0; k < at.size() && k < labels.size(); ++k) {
            float bounds[4] = {0, 0, 0, 0};
            painter->ComputeStringBounds(labels[k], bounds);
            const auto w = static_cast<double>(bounds[2]);
            const auto h = static_cast<double>(bounds[3]);
            const QPointF p = at[k];
            const QPointF corners[] = {{p.x() + kGap, p.y() + 2.0},     {p.x() + kGap, p.y() - h - 2.0},
                                       {p.x() - kGap - w, p.y() + 2.0}, {p.x() - kGap - w, p.y() - h - 2.0},
                                       {p.x() - w / 2, p.y() + kGap},   {p.x() - w / 2, p.y() - kGap - h},
                                       {p.x() + kGap, p.y() - h / 2},   {p.x() - kGap - w, p.y() - h / 2}};
            const auto free = [&](const QRectF& r) {
                for (const QRectF& other : placed)
                    if (r.intersects(other)) return false;
                for (std::size_t j = 0; j < at.size(); ++j)
                    if (j != k && r.intersects(QRectF(at[j].x() - kMarker, at[j].y() - kMarker, 2 * kMarker,
                                                      2 * kMarker)))
                        return false;
                return true;
            };
            QRectF chosen(corners[0], QSizeF(w, h));
            for (const QPointF& c : corners)
                if (free(QRectF(c, QSizeF(w, h)))) {
                    chosen = QRectF(c, QSizeF(w, h));
                    break;
                }
            placed.push_back(chosen);
            painter->DrawString(static_cast<float>(chosen.x()), static_cast<float>(chosen.y()), labels[k]);
        }
        return true;
    }

protected:
    PointLabels() = default;
    ~PointLabels() override = default;
};

void fillPath(vtkTable* t, const MultiAngleReport& report) {
    t->Initialize();
    for (const char* name : {"aspecular_deg", "a", "b"}) {
        vtkNew<vtkDoubleArray> column;
        column->SetName(name);
        t->AddColumn(column);
    }
    t->SetNumberOfRows(static_cast<vtkIdType>(report.colours.size()));
    for (std::size_t k = 0; k < report.colours.size(); ++k) {
        const auto row = static_cast<vtkIdType>(k);
        t->SetValue(row, 0, report.colours[k].aspecular_deg);
        t->SetValue(row, 1, report.colours[k].lab.a);
        t->SetValue(row, 2, report.colours[k].lab.b);
    }
    t->Modified();
}

}  // namespace

struct AbChart::Vtk {
    vtkNew<vtkContextView> view;
    vtkNew<vtkChartXY> chart;
    vtkNew<vtkTable> path;
    vtkNew<vtkTable> comparison;
    std::vector<vtkSmartPointer<vtkTable>> point_tables;  // one per geometry: its own colour
    vtkNew<PointLabels> labels;
};

AbChart::AbChart(QWidget* parent) : PlotWidget(parent) {
    runOnRenderThread([this] {
        m_vtk = std::make_unique<Vtk>();
        showChart(m_vtk->view, m_vtk->chart);
        m_vtk->chart->SetTitle("CIELAB a*b* at the multi-angle geometries (D65/10 deg), flop path");
        m_vtk->chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("a*");
        m_vtk->chart->GetAxis(vtkAxis::LEFT)->SetTitle("b*");
        m_vtk->chart->SetShowLegend(true);
        m_vtk->chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);  // the box is set in layoutForSize
        m_vtk->labels->chart = m_vtk->chart;
        m_vtk->view->GetScene()->AddItem(m_vtk->labels);  // over the chart
    });
    updateChart();
}

AbChart::~AbChart() {
    runOnRenderThread([this] { m_vtk.reset(); });
}

void AbChart::setBrdf(const SpectralBrdf& brdf) { setReport(multiAngleColours(brdf)); }

void AbChart::setReport(MultiAngleReport report) {
    m_report = std::move(report);
    updateChart();
}

void AbChart::setComparison(const SpectralBrdf& brdf, const QString& label) {
    setComparisonReport(multiAngleColours(brdf), label);
}

void AbChart::setComparisonReport(MultiAngleReport report, const QString& label) {
    m_comparison = std::move(report);
    m_comparison_label = label.isEmpty() ? QStringLiteral("comparison") : label;
    updateChart();
}

void AbChart::clearComparison() {
    m_comparison = {};
    m_comparison_label.clear();
    updateChart();
}

void AbChart::layoutForSize(int width_px, int height_px) {
    if (!m_vtk) return;
    // Room for the tick numbers and axis titles (left, bottom), the title
    // (top) and the legend (right): the rest is the square box of axes.
    constexpr float kLeft = 70.0F;
    constexpr float kBottom = 50.0F;
    constexpr float kTop = 40.0F;
    constexpr float kRight = 150.0F;
    const float room_w = static_cast<float>(width_px) - kLeft - kRight;
    const float room_h = static_cast<float>(height_px) - kBottom - kTop;
    const float side = std::max(40.0F, std::min(room_w, room_h));
    const float x0 = kLeft + std::max(0.0F, (room_w - side) / 2.0F);
    const float y0 = kBottom + std::max(0.0F, (room_h - side) / 2.0F);
    m_vtk->chart->SetSize(vtkRectf(x0, y0, side, side));
    // The legend right of the box, its lower left corner at mid-height
    // (vtkChartXY places no legend itself when its alignment is CUSTOM).
    vtkChartLegend* legend = m_vtk->chart->GetLegend();
    legend->SetHorizontalAlignment(vtkChartLegend::CUSTOM);
    legend->SetVerticalAlignment(vtkChartLegend::CUSTOM);
    legend->SetPoint(x0 + side + 12.0F, y0 + side / 2.0F);
}

std::vector<QRectF> AbChart::labelRects() const {
    std::vector<QRectF> out;
    runOnRenderThread([this, &out] {
        if (m_vtk) out = m_vtk->labels->placed;
    });
    return out;
}

std::vector<double> AbChart::pathAspecularDeg() const {
    std::vector<double> out;
    runOnRenderThread([this, &out] {
        for (vtkIdType row = 0; row < m_vtk->path->GetNumberOfRows(); ++row)
            out.push_back(m_vtk->path->GetValue(row, 0).ToDouble());
    });
    return out;
}

void AbChart::updateChart() {
    // The render thread draws copies: the GUI thread may change the reports meanwhile.
    onRenderThread([this, report = m_report, comparison = m_comparison, label = m_comparison_label] {
        fillPath(m_vtk->path, report);
        fillPath(m_vtk->comparison, comparison);
        vtkChartXY* chart = m_vtk->chart;
        chart->ClearPlots();

        if (!report.colours.empty()) {
            vtkPlot* line = chart->AddPlot(vtkChart::LINE);
            line->SetInputData(m_vtk->path, 1, 2);
            line->SetColor(60, 60, 60, 255);
            line->SetWidth(2.0F);
            line->SetLabel("current");
        }
        if (!comparison.colours.empty()) {
            vtkPlot* line = chart->AddPlot(vtkChart::LINE);
            line->SetInputData(m_vtk->comparison, 1, 2);
            line->SetColor(60, 60, 60, 255);
            line->SetWidth(2.0F);
            line->GetPen()->SetLineType(vtkPen::DASH_LINE);
            // Short in the legend ("full model"), which must fit right of the box.
            line->SetLabel(label.section(QStringLiteral(" ("), 0, 0).toStdString());
            if (auto* points = vtkPlotPoints::SafeDownCast(line)) {
                points->SetMarkerStyle(vtkPlotPoints::CROSS);
                points->SetMarkerSize(9.0F);
            }
        }
        // Each geometry's point in its own colour (hue and saturation: plot_data.h
        // displayColour; XYZ for the 10° observer through the sRGB matrix, for display only).
        m_vtk->point_tables.clear();
        m_vtk->labels->points.clear();
        m_vtk->labels->labels.clear();
        for (const MultiAngleColour& c : report.colours) {
            auto table = vtkSmartPointer<vtkTable>::New();
            for (const char* name : {"a", "b"}) {
                vtkNew<vtkDoubleArray> column;
                column->SetName(name);
                table->AddColumn(column);
            }
            table->SetNumberOfRows(1);
            table->SetValue(0, 0, c.lab.a);
            table->SetValue(0, 1, c.lab.b);
            vtkPlot* point = chart->AddPlot(vtkChart::POINTS);
            point->SetInputData(table, 0, 1);
            const Rgb8 colour = displayColour(xyzToLinearSrgb(c.xyz));
            point->SetColor(colour.r, colour.g, colour.b, 255);
            point->SetLegendVisibility(false);
            if (auto* p = vtkPlotPoints::SafeDownCast(point)) {
                p->SetMarkerStyle(vtkPlotPoints::CIRCLE);
                p->SetMarkerSize(14.0F);
            }
            m_vtk->point_tables.push_back(table);
            m_vtk->labels->points.emplace_back(c.lab.a, c.lab.b);
            m_vtk->labels->labels.push_back(geometryName(c.aspecular_deg));
        }

        // The same span on both axes, the origin (neutral grey) always in view.
        double lo_a = 0.0;
        double hi_a = 0.0;
        double lo_b = 0.0;
        double hi_b = 0.0;
        for (const MultiAngleReport* r : {&report, &comparison})
            for (const MultiAngleColour& c : r->colours) {
                lo_a = std::min(lo_a, c.lab.a);
                hi_a = std::max(hi_a, c.lab.a);
                lo_b = std::min(lo_b, c.lab.b);
                hi_b = std::max(hi_b, c.lab.b);
            }
        const double half = std::max({hi_a - lo_a, hi_b - lo_b, 10.0}) * 0.6;
        const double mid_a = 0.5 * (lo_a + hi_a);
        const double mid_b = 0.5 * (lo_b + hi_b);
        for (auto [axis, mid] : {std::pair{vtkAxis::BOTTOM, mid_a}, std::pair{vtkAxis::LEFT, mid_b}}) {
            vtkAxis* a = chart->GetAxis(axis);
            a->SetBehavior(vtkAxis::FIXED);
            a->SetRange(mid - half, mid + half);
        }
    });
    emit dataChanged();
}

bool AbChart::exportCsv(const QString& path) const {
    std::vector<QStringList> rows;
    const auto add = [&rows](const MultiAngleReport& report, const QString& series) {
        for (const MultiAngleColour& c : report.colours)
            rows.push_back({csvText(series), csvNumber(c.aspecular_deg), csvNumber(c.lab.L),
                            csvNumber(c.lab.a), csvNumber(c.lab.b), csvNumber(c.xyz.X), csvNumber(c.xyz.Y),
                            csvNumber(c.xyz.Z)});
    };
    add(m_report, QStringLiteral("current"));
    add(m_comparison, m_comparison_label);
    return writeCsv(path, {"series", "aspecular_deg", "L", "a", "b", "X", "Y", "Z"}, rows);
}

}  // namespace paintlab::gui
