#include "inplane_plot.h"

#include "paintlab/engine/brdf_colour.h"
#include "paintlab/engine/layered_brdf.h"

#include <QSaveFile>
#include <QTextStream>

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>

namespace paintlab::gui {

struct InplanePlot::Vtk {
    vtkNew<vtkGenericOpenGLRenderWindow> window;
    vtkNew<vtkContextView> view;
    vtkNew<vtkChartXY> chart;
    vtkNew<vtkTable> table;
};

namespace {
constexpr double kIncidenceDeg = 45.0;
constexpr int kAngles = 69;  // -85 .. 85 deg in 2.5 deg steps
}  // namespace

InplanePlot::InplanePlot(QWidget* parent) : QOpenGLWidget(parent), m_vtk(std::make_unique<Vtk>()) {
    m_vtk->view->SetRenderWindow(m_vtk->window);
    m_vtk->view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
    m_vtk->view->GetScene()->AddItem(m_vtk->chart);
    m_vtk->chart->SetTitle("In-plane reflectance factor, light at 45 deg");
    m_vtk->chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("view angle (deg, negative: light side)");
    m_vtk->chart->GetAxis(vtkAxis::LEFT)->SetTitle("pi f");
    m_vtk->chart->SetShowLegend(true);
    for (const char* name : {"view_deg", "R", "G", "B", "Y"}) {
        vtkNew<vtkDoubleArray> column;
        column->SetName(name);
        m_vtk->table->AddColumn(column);
    }
    setMinimumSize(320, 240);
}

InplanePlot::~InplanePlot() {
    makeCurrent();  // VTK releases its GL resources in the widget's context
    m_vtk.reset();
    doneCurrent();
}

void InplanePlot::setBrdf(const LayeredBrdf& brdf) {
    Curve c;
    const Direction wi = directionFromAnglesDeg(kIncidenceDeg, 180.0);
    for (int k = 0; k < kAngles; ++k) {
        const double view = -85.0 + 2.5 * k;
        // In the plane of incidence: positive angles on the far side (the specular side).
        const Direction wo = directionFromAnglesDeg(std::abs(view), view >= 0.0 ? 0.0 : 180.0);
        const SpectralColour colour = reflectanceFactorColour(brdf, wi, wo);
        c.view_deg.push_back(view);
        c.r.push_back(colour.linear_srgb.r);
        c.g.push_back(colour.linear_srgb.g);
        c.b.push_back(colour.linear_srgb.b);
        c.y.push_back(colour.xyz.Y);
    }
    m_curve = std::move(c);
    updateChart();
}

void InplanePlot::setLogScale(bool log_scale) {
    m_log_scale = log_scale;
    updateChart();
}

void InplanePlot::updateChart() {
    vtkTable* t = m_vtk->table;
    const auto n = static_cast<vtkIdType>(m_curve.view_deg.size());
    t->SetNumberOfRows(n);
    // A log axis cannot show zero: the floor is far below any visible reflectance.
    const auto shown = [this](double v) { return m_log_scale ? std::max(v, 1e-6) : v; };
    for (vtkIdType i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        t->SetValue(i, 0, m_curve.view_deg[k]);
        t->SetValue(i, 1, shown(m_curve.r[k]));
        t->SetValue(i, 2, shown(m_curve.g[k]));
        t->SetValue(i, 3, shown(m_curve.b[k]));
        t->SetValue(i, 4, shown(m_curve.y[k]));
    }
    t->Modified();
    vtkChartXY* chart = m_vtk->chart;
    // The four lines are made once and then follow the table, rather than
    // re-created with their GL state on every update.
    if (chart->GetNumberOfPlots() == 0) {
        const unsigned char colours[4][3] = {{200, 30, 30}, {30, 150, 30}, {30, 60, 200}, {20, 20, 20}};
        for (int s = 0; s < 4; ++s) {
            vtkPlot* line = chart->AddPlot(vtkChart::LINE);
            line->SetInputData(t, 0, s + 1);
            line->SetColor(colours[s][0], colours[s][1], colours[s][2], 255);
            line->SetWidth(s == 3 ? 2.5F : 1.5F);
        }
    }
    chart->GetAxis(vtkAxis::LEFT)->SetLogScale(m_log_scale);
    chart->RecalculateBounds();
    update();
}

bool InplanePlot::exportCsv(const QString& path) const {
    QSaveFile file(path);  // atomic: the old file stays until the new one is complete
    if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) return false;
    QTextStream out(&file);
    out << "view_deg,R,G,B,Y\n";
    for (std::size_t i = 0; i < m_curve.view_deg.size(); ++i)
        out << m_curve.view_deg[i] << ',' << m_curve.r[i] << ',' << m_curve.g[i] << ',' << m_curve.b[i] << ','
            << m_curve.y[i] << '\n';
    out.flush();
    return file.commit();
}

void InplanePlot::initializeGL() {
    // Qt owns the context; VTK draws into whatever framebuffer is bound when
    // it renders (the widget's) and loads its GL functions from this context.
    m_vtk->window->SetOwnContext(0);
    m_vtk->window->SetReadyForRendering(true);
    m_vtk->window->SetIsCurrent(true);
    m_vtk->window->SetFrameBlitModeToBlitToCurrent();
    m_vtk->window->InitializeFromCurrentContext();
}

void InplanePlot::resizeGL(int w, int h) {
    const double ratio = devicePixelRatioF();
    m_vtk->window->SetSize(static_cast<int>(w * ratio), static_cast<int>(h * ratio));
}

void InplanePlot::paintGL() {
    m_vtk->window->SetIsCurrent(true);
    m_vtk->window->Render();
}

}  // namespace paintlab::gui
