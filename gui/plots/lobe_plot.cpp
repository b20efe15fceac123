#include "lobe_plot.h"

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <QElapsedTimer>
#include <QMouseEvent>
#include <QWheelEvent>

#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLineSource.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRegularPolygonSource.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::gui {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kLogDecades = 3.0;  // the log radius spans 1e-3 .. 1 of the peak

// A line from a to b with its own actor.
struct Line {
    vtkNew<vtkLineSource> source;
    vtkNew<vtkPolyDataMapper> mapper;
    vtkNew<vtkActor> actor;
    Line(vtkRenderer* renderer, double r, double g, double b, float width) {
        mapper->SetInputConnection(source->GetOutputPort());
        actor->SetMapper(mapper);
        actor->GetProperty()->SetColor(r, g, b);
        actor->GetProperty()->SetLineWidth(width);
        actor->GetProperty()->SetLighting(false);
        renderer->AddActor(actor);
    }
    void set(const double a[3], const double b[3]) {
        source->SetPoint1(a[0], a[1], a[2]);
        source->SetPoint2(b[0], b[1], b[2]);
    }
};

void label(vtkBillboardTextActor3D* text, vtkRenderer* renderer, const char* what) {
    text->SetInput(what);
    text->GetTextProperty()->SetFontSize(15);
    text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    text->GetTextProperty()->SetJustificationToCentered();
    renderer->AddActor(text);
}

}  // namespace

struct LobePlot::Vtk {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkPolyData> lobe;
    vtkNew<vtkPolyDataNormals> normals;
    vtkNew<vtkPolyDataMapper> lobe_mapper;
    vtkNew<vtkActor> lobe_actor;
    vtkNew<vtkRegularPolygonSource> disk;
    vtkNew<vtkPolyDataMapper> disk_mapper;
    vtkNew<vtkActor> disk_actor;
    vtkNew<vtkRegularPolygonSource> rim;
    vtkNew<vtkPolyDataMapper> rim_mapper;
    vtkNew<vtkActor> rim_actor;
    Line normal;
    Line light;
    Line mirror;
    vtkNew<vtkBillboardTextActor3D> normal_label;
    vtkNew<vtkBillboardTextActor3D> light_label;
    vtkNew<vtkBillboardTextActor3D> mirror_label;
    vtkNew<vtkTextActor> title;

    Vtk()
        : normal(renderer, 0.2, 0.2, 0.2, 1.5F), light(renderer, 0.95, 0.6, 0.0, 4.0F),
          mirror(renderer, 0.45, 0.45, 0.45, 2.0F) {}
};

LobePlot::LobePlot(QWidget* parent) : PlotWidget(parent) {
    runOnRenderThread([this] {
        m_vtk = std::make_unique<Vtk>();
        Vtk& v = *m_vtk;
        renderWindow()->AddRenderer(v.renderer);
        v.renderer->SetBackground(1.0, 1.0, 1.0);
        v.renderer->SetBackground2(0.86, 0.89, 0.93);
        v.renderer->GradientBackgroundOn();

        v.normals->SetInputData(v.lobe);
        v.normals->SplittingOff();
        v.normals->ConsistencyOn();
        v.lobe_mapper->SetInputConnection(v.normals->GetOutputPort());
        v.lobe_mapper->SetColorModeToDirectScalars();
        v.lobe_mapper->ScalarVisibilityOn();
        v.lobe_actor->SetMapper(v.lobe_mapper);
        v.lobe_actor->GetProperty()->SetAmbient(0.35);
        v.lobe_actor->GetProperty()->SetDiffuse(0.7);
        v.lobe_actor->GetProperty()->SetSpecular(0.15);
        v.renderer->AddActor(v.lobe_actor);

        // The surface: a grey disk just below z = 0 and its rim at radius 1.
        v.disk->SetNumberOfSides(96);
        v.disk->SetRadius(1.0);
        v.disk->SetCenter(0.0, 0.0, -0.002);
        v.disk_mapper->SetInputConnection(v.disk->GetOutputPort());
        v.disk_actor->SetMapper(v.disk_mapper);
        v.disk_actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
        v.disk_actor->GetProperty()->SetLighting(false);
        v.renderer->AddActor(v.disk_actor);
        v.rim->SetNumberOfSides(96);
        v.rim->SetRadius(1.0);
        v.rim->GeneratePolygonOff();
        v.rim->GeneratePolylineOn();
        v.rim_mapper->SetInputConnection(v.rim->GetOutputPort());
        v.rim_actor->SetMapper(v.rim_mapper);
        v.rim_actor->GetProperty()->SetColor(0.35, 0.35, 0.35);
        v.rim_actor->GetProperty()->SetLighting(false);
        v.renderer->AddActor(v.rim_actor);

        label(v.normal_label, v.renderer, "normal");
        label(v.light_label, v.renderer, "light");
        label(v.mirror_label, v.renderer, "mirror");
        v.title->GetTextProperty()->SetFontSize(15);
        v.title->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
        v.title->SetDisplayPosition(10, 10);
        v.renderer->AddActor2D(v.title);
    });

    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(true);  // moves reach the widget whatever the event's button state says
    resetView();
    updateScene();
}

LobePlot::~LobePlot() {
    runOnRenderThread([this] { m_vtk.reset(); });
}

void LobePlot::compute(const LayeredBrdf& brdf) { m_grid = lobeGrid(brdf, m_theta_i_deg, m_phi_i_deg); }

void LobePlot::setBrdf(const LayeredBrdf& brdf) {
    QElapsedTimer timer;
    timer.start();
    m_brdf.reset();
    compute(brdf);
    updateScene();
    m_update_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

void LobePlot::setBrdf(std::shared_ptr<const LayeredBrdf> brdf) {
    QElapsedTimer timer;
    timer.start();
    m_brdf = std::move(brdf);
    if (m_brdf) compute(*m_brdf);
    updateScene();
    m_update_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

void LobePlot::setGrid(LobeGrid grid) {
    QElapsedTimer timer;
    timer.start();
    m_brdf.reset();
    m_grid = std::move(grid);
    m_theta_i_deg = m_grid.theta_i_deg;
    m_phi_i_deg = m_grid.phi_i_deg;
    updateScene();
    m_update_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

void LobePlot::setIncidence(double theta_i_deg, double phi_i_deg) {
    m_theta_i_deg = std::clamp(theta_i_deg, 0.0, 85.0);
    m_phi_i_deg = phi_i_deg;
    QElapsedTimer timer;
    timer.start();
    if (m_brdf) compute(*m_brdf);
    updateScene();
    m_update_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

void LobePlot::setLogRadius(bool log_radius) {
    m_log_radius = log_radius;
    updateScene();
}

void LobePlot::resetView() {
    onRenderThread([this] {
        vtkCamera* camera = m_vtk->renderer->GetActiveCamera();
        camera->SetFocalPoint(0.0, 0.0, 0.4);
        camera->SetPosition(1.4, -4.0, 2.5);
        camera->SetViewUp(0.0, 0.0, 1.0);
        camera->SetViewAngle(30.0);
        m_vtk->renderer->ResetCameraClippingRange();
    });
}

std::array<double, 3> LobePlot::cameraPosition() const {
    std::array<double, 3> p{};
    runOnRenderThread([this, &p] { m_vtk->renderer->GetActiveCamera()->GetPosition(p.data()); });
    return p;
}

void LobePlot::updateScene() {
    const QString title = tr("BRDF lobe, light at theta %1 deg, phi %2 deg\nradius: CIE Y of the reflectance "
                             "factor%3 (peak %4); colour: its hue")
                              .arg(m_theta_i_deg, 0, 'g', 3)
                              .arg(m_phi_i_deg, 0, 'g', 3)
                              .arg(m_log_radius ? tr(", log over 3 decades") : QString())
                              .arg(m_grid.max_y, 0, 'g', 3);
    // The render thread builds the surface from copies: the GUI thread may change them meanwhile.
    onRenderThread([this, g = m_grid, log_radius = m_log_radius,
                    wi = directionFromAnglesDeg(m_theta_i_deg, m_phi_i_deg), title = title.toStdString()] {
        Vtk& v = *m_vtk;
        const std::size_t rings = g.theta_o_deg.size();
        const std::size_t azimuths = g.phi_o_deg.size();
        vtkNew<vtkPoints> points;
        vtkNew<vtkUnsignedCharArray> colours;
        colours->SetName("colour");
        colours->SetNumberOfComponents(3);
        vtkNew<vtkCellArray> triangles;
        if (rings >= 2 && azimuths >= 2 && g.y.size() == rings * azimuths) {
            const auto count = static_cast<vtkIdType>(rings) * static_cast<vtkIdType>(azimuths);
            points->SetNumberOfPoints(count);
            colours->SetNumberOfTuples(count);
            for (std::size_t t = 0; t < rings; ++t) {
                const double theta = g.theta_o_deg[t] * kDeg;
                for (std::size_t p = 0; p < azimuths; ++p) {
                    const std::size_t k = t * azimuths + p;
                    double r = g.max_y > 0.0 ? g.y[k] / g.max_y : 0.0;
                    if (log_radius) r = r > 0.0 ? std::max(0.0, 1.0 + std::log10(r) / kLogDecades) : 0.0;
                    const double phi = g.phi_o_deg[p] * kDeg;
                    const auto id = static_cast<vtkIdType>(k);
                    points->SetPoint(id, r * std::sin(theta) * std::cos(phi),
                                     r * std::sin(theta) * std::sin(phi), r * std::cos(theta));
                    const Rgb8 c = displayColour(g.linear_srgb[k]);
                    const unsigned char rgb[3] = {c.r, c.g, c.b};
                    colours->SetTypedTuple(id, rgb);
                }
            }
            const auto vertex = [azimuths](std::size_t t, std::size_t p) {
                return static_cast<vtkIdType>(t) * static_cast<vtkIdType>(azimuths) +
                       static_cast<vtkIdType>(p % azimuths);
            };
            for (std::size_t t = 0; t + 1 < rings; ++t)
                for (std::size_t p = 0; p < azimuths; ++p) {
                    const vtkIdType a[3] = {vertex(t, p), vertex(t + 1, p), vertex(t + 1, p + 1)};
                    const vtkIdType b[3] = {vertex(t, p), vertex(t + 1, p + 1), vertex(t, p + 1)};
                    triangles->InsertNextCell(3, a);
                    triangles->InsertNextCell(3, b);
                }
        }
        v.lobe->SetPoints(points);
        v.lobe->SetPolys(triangles);
        v.lobe->GetPointData()->SetScalars(colours);
        v.lobe->Modified();

        const double origin[3] = {0.0, 0.0, 0.0};
        const double up[3] = {0.0, 0.0, 1.25};
        const double light[3] = {1.3 * wi.x, 1.3 * wi.y, 1.3 * wi.z};
        const double mirror[3] = {-1.15 * wi.x, -1.15 * wi.y, 1.15 * wi.z};
        v.normal.set(origin, up);
        v.light.set(origin, light);
        v.mirror.set(origin, mirror);
        v.normal_label->SetPosition(0.0, 0.0, 1.35);
        v.light_label->SetPosition(1.42 * wi.x, 1.42 * wi.y, 1.42 * wi.z);
        v.mirror_label->SetPosition(-1.27 * wi.x, -1.27 * wi.y, 1.27 * wi.z);
        v.title->SetInput(title.c_str());
        v.renderer->ResetCameraClippingRange();
    });
    emit dataChanged();
}

void LobePlot::mousePressEvent(QMouseEvent* event) {
    m_drag = event->button();
    m_last_mouse = event->position().toPoint();
    event->accept();
}

void LobePlot::mouseMoveEvent(QMouseEvent* event) {
    const QPoint now = event->position().toPoint();
    const QPoint d = now - m_last_mouse;
    m_last_mouse = now;
    if (m_drag == Qt::LeftButton) {
        // As vtkInteractorStyleTrackballCamera::Rotate: a full widget height is 180 degrees.
        const double per_pixel = 180.0 / std::max(1, height());
        onRenderThread([this, azimuth = -d.x() * per_pixel, elevation = d.y() * per_pixel] {
            vtkCamera* camera = m_vtk->renderer->GetActiveCamera();
            camera->Azimuth(azimuth);
            camera->Elevation(elevation);
            camera->OrthogonalizeViewUp();
            m_vtk->renderer->ResetCameraClippingRange();
        });
    } else if (m_drag == Qt::RightButton) {
        dolly(std::pow(1.01, -d.y()));
    } else {
        return;
    }
    event->accept();
}

void LobePlot::mouseReleaseEvent(QMouseEvent* event) {
    m_drag = Qt::NoButton;
    event->accept();
}

void LobePlot::mouseDoubleClickEvent(QMouseEvent* event) {
    resetView();
    event->accept();
}

void LobePlot::wheelEvent(QWheelEvent* event) {
    dolly(std::pow(1.1, event->angleDelta().y() / 120.0));
    event->accept();
}

void LobePlot::dolly(double factor) {
    onRenderThread([this, factor] {
        m_vtk->renderer->GetActiveCamera()->Dolly(factor);
        m_vtk->renderer->ResetCameraClippingRange();
    });
}

bool LobePlot::exportCsv(const QString& path) const {
    std::vector<QStringList> rows;
    const LobeGrid& g = m_grid;
    for (std::size_t t = 0; t < g.theta_o_deg.size(); ++t)
        for (std::size_t p = 0; p < g.phi_o_deg.size(); ++p) {
            const std::size_t k = t * g.phi_o_deg.size() + p;
            if (k >= g.y.size()) break;
            rows.push_back({csvNumber(g.theta_i_deg), csvNumber(g.phi_i_deg), csvNumber(g.theta_o_deg[t]),
                            csvNumber(g.phi_o_deg[p]), csvNumber(g.linear_srgb[k].r),
                            csvNumber(g.linear_srgb[k].g), csvNumber(g.linear_srgb[k].b), csvNumber(g.y[k])});
        }
    return writeCsv(path, {"theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg", "R", "G", "B", "Y"}, rows);
}

}  // namespace paintlab::gui
