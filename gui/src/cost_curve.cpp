// The fit's cost curve (cost_curve.h).

#include "cost_curve.h"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

CostCurve::CostCurve(QWidget* parent) : QWidget(parent) {
    setObjectName("match_cost_curve");
    setToolTip(tr("Best cost (0.5 sum of squared whitened residuals) against model evaluations, log scale"));
}

void CostCurve::clear() {
    m_points.clear();
    update();
}

void CostCurve::add(long evaluations, double best_cost) {
    if (!std::isfinite(best_cost) || best_cost <= 0.0) return;
    m_points.push_back({evaluations, best_cost});
    update();
}

void CostCurve::paintEvent(QPaintEvent* /*event*/) {
    QPainter painter(this);
    painter.fillRect(rect(), palette().base());
    painter.setPen(palette().mid().color());
    painter.drawRect(rect().adjusted(0, 0, -1, -1));
    if (m_points.size() < 2) {
        painter.setPen(palette().placeholderText().color());
        painter.drawText(rect(), Qt::AlignCenter, tr("cost curve"));
        return;
    }
    double lo = std::log10(m_points.front().cost);
    double hi = lo;
    for (const auto& p : m_points) {
        lo = std::min(lo, std::log10(p.cost));
        hi = std::max(hi, std::log10(p.cost));
    }
    if (hi - lo < 1e-9) hi = lo + 1.0;
    const double e0 = static_cast<double>(m_points.front().evaluations);
    const double e1 = std::max(e0 + 1.0, static_cast<double>(m_points.back().evaluations));
    const QRectF box = QRectF(rect()).adjusted(4, 4, -4, -4);
    QPainterPath path;
    for (std::size_t i = 0; i < m_points.size(); ++i) {
        const double x =
            box.left() + box.width() * (static_cast<double>(m_points[i].evaluations) - e0) / (e1 - e0);
        const double y = box.bottom() - box.height() * (std::log10(m_points[i].cost) - lo) / (hi - lo);
        if (i == 0)
            path.moveTo(x, y);
        else
            path.lineTo(x, y);
    }
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(palette().highlight().color(), 1.5));
    painter.drawPath(path);
    painter.setPen(palette().text().color());
    painter.drawText(box, Qt::AlignRight | Qt::AlignTop, tr("best %1").arg(m_points.back().cost, 0, 'g', 3));
}

}  // namespace paintlab::gui
