#include "depth_profile_plot.h"

#include "depth_profile_edit.h"
#include "spectrum_chart.h"

#include "paintlab/engine/recipe_paths.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPaintEvent>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

namespace {

constexpr double kNodeRadius = 5.0;
constexpr double kPickRadius = 9.0;  // a node is grabbed within this many pixels

}  // namespace

DepthProfilePlot::DepthProfilePlot(QWidget* parent) : QWidget(parent) {
    setObjectName("depth_profile_plot");
    setAutoFillBackground(true);
    setBackgroundRole(QPalette::Base);
    setFocusPolicy(Qt::StrongFocus);  // Delete removes the selected node
    setMouseTracking(true);           // the cursor shows when a node is within reach
    setCursor(Qt::CrossCursor);
    m_profile = presetProfile(DepthProfilePreset::Uniform);
}

void DepthProfilePlot::setProfile(const DepthProfile& profile, bool stored) {
    const bool same_nodes = profile.depth.size() == m_profile.depth.size();
    m_profile = profile;
    m_stored = stored;
    if (!same_nodes) {
        m_dragged = -1;
        m_moved = false;
    }
    if (m_selected >= static_cast<int>(m_profile.depth.size())) selectNode(-1);
    if (m_dragged < 0) updateAxis();
    update();
}

void DepthProfilePlot::setThicknessUm(double thickness_um) {
    m_thickness_um = thickness_um;
    update();
}

void DepthProfilePlot::selectNode(int node) {
    if (node == m_selected) return;
    m_selected = node;
    update();
    emit selectionChanged(node);
}

void DepthProfilePlot::updateAxis() {
    double top = 1.0;
    for (const double w : m_profile.weight) top = std::max(top, w);
    m_axis_max = top * 1.25;  // room above the highest node to drag it up
}

QString DepthProfilePlot::depthAxisTitle() const {
    if (m_thickness_um > 0.0)
        return tr("depth from the top of the layer (µm), layer %1 µm thick").arg(m_thickness_um, 0, 'g', 4);
    return tr("relative depth from the top of the layer (0) to its bottom (1)");
}

QRectF DepthProfilePlot::plotRect() const {
    const QFontMetrics fm = fontMetrics();
    const double left = fm.horizontalAdvance(QStringLiteral("000.0")) + 2.0 * fm.height();
    const double bottom = 2.5 * fm.height() + 4.0;
    const double top = fm.height() + 6.0;
    const double right = 14.0;
    return {left, top, std::max(10.0, width() - left - right), std::max(10.0, height() - top - bottom)};
}

QPointF DepthProfilePlot::nodePosition(std::size_t node) const {
    const QRectF r = plotRect();
    if (node >= m_profile.depth.size() || node >= m_profile.weight.size()) return r.center();
    return {r.left() + m_profile.depth[node] * r.width(),
            r.bottom() - m_profile.weight[node] / m_axis_max * r.height()};
}

QPointF DepthProfilePlot::valueAt(QPointF point) const {
    const QRectF r = plotRect();
    return {(point.x() - r.left()) / r.width(), (r.bottom() - point.y()) / r.height() * m_axis_max};
}

int DepthProfilePlot::nodeAt(QPointF point) const {
    int best = -1;
    double best_distance = kPickRadius;
    for (std::size_t i = 0; i < m_profile.depth.size(); ++i) {
        const QPointF d = nodePosition(i) - point;
        const double distance = std::hypot(d.x(), d.y());
        if (distance <= best_distance) {
            best = static_cast<int>(i);
            best_distance = distance;
        }
    }
    return best;
}

void DepthProfilePlot::removeNode(int node) {
    if (node < 0) return;
    const std::optional<DepthProfile> removed = withNodeRemoved(m_profile, static_cast<std::size_t>(node));
    if (!removed) {
        emit refused(tr("%1: the nodes at the top (0) and the bottom (1) of the layer stay; drag them to "
                        "change their weight")
                         .arg(QString::fromStdString(
                             elementPath("depth_profile", "depth", static_cast<std::size_t>(node)))));
        return;
    }
    selectNode(-1);
    emit edited(*removed);
}

void DepthProfilePlot::mousePressEvent(QMouseEvent* event) {
    const int node = nodeAt(event->position());
    if (event->button() == Qt::RightButton) {
        removeNode(node);
        return;
    }
    if (event->button() != Qt::LeftButton) return;
    selectNode(node);
    m_dragged = node;
    m_moved = false;
    if (node >= 0) setCursor(Qt::ClosedHandCursor);
}

void DepthProfilePlot::mouseMoveEvent(QMouseEvent* event) {
    if (m_dragged < 0 || !(event->buttons() & Qt::LeftButton)) {
        setCursor(nodeAt(event->position()) >= 0 ? Qt::OpenHandCursor : Qt::CrossCursor);
        return;
    }
    const QPointF v = valueAt(event->position());
    const DepthProfile moved = withNodeMoved(m_profile, static_cast<std::size_t>(m_dragged), v.x(),
                                             std::clamp(v.y(), 0.0, m_axis_max));
    if (moved == m_profile) return;
    m_moved = true;
    emit nodeDragged(moved);
}

void DepthProfilePlot::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton || m_dragged < 0) return;
    const bool moved = m_moved;
    setCursor(Qt::OpenHandCursor);  // still over the node just let go
    m_dragged = -1;
    m_moved = false;
    updateAxis();
    update();
    if (moved) emit dragReleased(m_profile);
}

void DepthProfilePlot::mouseDoubleClickEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton || nodeAt(event->position()) >= 0) return;
    m_dragged = -1;
    const QPointF v = valueAt(event->position());
    std::size_t index = 0;
    const std::optional<DepthProfile> added =
        withNodeInserted(m_profile, v.x(), std::clamp(v.y(), 0.0, m_axis_max), &index);
    if (!added) {
        emit refused(tr("depth_profile > depth: a new node must lie inside the layer (between 0 and 1), "
                        "apart from the other nodes"));
        return;
    }
    emit edited(*added);
    if (m_profile == *added) selectNode(static_cast<int>(index));
}

void DepthProfilePlot::keyPressEvent(QKeyEvent* event) {
    if (event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) {
        removeNode(m_selected);
        return;
    }
    QWidget::keyPressEvent(event);
}

void DepthProfilePlot::paintEvent(QPaintEvent* /*event*/) {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    const QFontMetrics fm = p.fontMetrics();
    const QColor ink = palette().color(QPalette::Text);
    const QColor grid = palette().color(QPalette::Mid);
    const QColor accent = palette().color(QPalette::Highlight);
    const QRectF r = plotRect();

    // Axes and ticks: depth in µm when the thickness is known, weight from 0.
    p.setPen(grid);
    p.drawRect(r);
    const double thickness = m_thickness_um > 0.0 ? m_thickness_um : 1.0;
    for (const double t : niceTicks(0.0, thickness, 5)) {
        const double x = r.left() + t / thickness * r.width();
        p.setPen(QPen(grid, 1.0, Qt::DotLine));
        p.drawLine(QPointF(x, r.top()), QPointF(x, r.bottom()));
        p.setPen(ink);
        const QString label = QString::number(t, 'g', 4);
        p.drawText(QPointF(x - fm.horizontalAdvance(label) / 2.0, r.bottom() + fm.ascent() + 3.0), label);
    }
    for (const double t : niceTicks(0.0, m_axis_max, 4)) {
        const double y = r.bottom() - t / m_axis_max * r.height();
        p.setPen(QPen(grid, 1.0, Qt::DotLine));
        p.drawLine(QPointF(r.left(), y), QPointF(r.right(), y));
        p.setPen(ink);
        const QString label = QString::number(t, 'g', 3);
        p.drawText(QPointF(r.left() - fm.horizontalAdvance(label) - 4.0, y + fm.ascent() / 2.0 - 1.0), label);
    }
    p.setPen(ink);
    const QString x_title = depthAxisTitle();
    p.drawText(QPointF(r.center().x() - fm.horizontalAdvance(x_title) / 2.0,
                       r.bottom() + fm.height() + fm.ascent() + 5.0),
               x_title);
    p.save();
    p.translate(fm.ascent() + 1.0, r.center().y());
    p.rotate(-90.0);
    const QString y_title = tr("weight w");
    p.drawText(QPointF(-fm.horizontalAdvance(y_title) / 2.0, 0.0), y_title);
    p.restore();
    const QString note = m_stored ? tr("drag nodes; double-click adds, right-click or Delete removes")
                                  : tr("uniform (no profile stored): drag a node to shape it");
    p.setPen(palette().color(QPalette::PlaceholderText));
    p.drawText(QPointF(r.left(), r.top() - 4.0), note);
    if (m_profile.depth.size() < 2 || m_profile.depth.size() != m_profile.weight.size()) return;

    // The mean weight: the level a uniform profile with as much material would have.
    const double mean = m_profile.meanWeight();
    const double mean_y = r.bottom() - std::min(mean, m_axis_max) / m_axis_max * r.height();
    p.setPen(QPen(accent, 1.0, Qt::DashLine));
    p.drawLine(QPointF(r.left(), mean_y), QPointF(r.right(), mean_y));
    p.drawText(QPointF(r.right() - fm.horizontalAdvance(tr("mean")) - 3.0, mean_y - 3.0), tr("mean"));

    // The curve (piecewise linear, as the engine interpolates) and the area under it.
    QPainterPath curve;
    for (std::size_t i = 0; i < m_profile.depth.size(); ++i) {
        if (i == 0) {
            curve.moveTo(nodePosition(i));
        } else {
            curve.lineTo(nodePosition(i));
        }
    }
    QPainterPath area = curve;
    area.lineTo(r.bottomRight());
    area.lineTo(r.bottomLeft());
    area.closeSubpath();
    QColor fill = accent;
    fill.setAlpha(40);
    p.fillPath(area, fill);
    p.setPen(QPen(m_stored ? ink : grid, 2.0, m_stored ? Qt::SolidLine : Qt::DashLine));
    p.drawPath(curve);
    for (std::size_t i = 0; i < m_profile.depth.size(); ++i) {
        const bool selected = static_cast<int>(i) == m_selected;
        p.setPen(QPen(ink, 1.5));
        p.setBrush(selected ? accent : palette().color(QPalette::Base));
        const double radius = selected ? kNodeRadius + 1.5 : kNodeRadius;
        p.drawEllipse(nodePosition(i), radius, radius);
    }
}

}  // namespace paintlab::gui
