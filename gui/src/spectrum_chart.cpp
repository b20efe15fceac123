#include "spectrum_chart.h"

#include "paintlab/engine/spectrum.h"

#include <QPaintEvent>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <utility>

namespace paintlab::gui {

std::vector<double> niceTicks(double lo, double hi, int count) {
    if (!(hi > lo) || count < 1) return {lo};
    const double raw = (hi - lo) / count;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    double step = power;
    for (const double m : {1.0, 2.0, 5.0, 10.0}) {
        step = m * power;
        if (step >= raw) break;
    }
    std::vector<double> ticks;
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
        ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    return ticks;
}

SpectrumChart::SpectrumChart(QWidget* parent) : QWidget(parent) {
    setObjectName("spectrum_chart");
    setAutoFillBackground(true);
    setBackgroundRole(QPalette::Base);
}

void SpectrumChart::setSpectrum(const QString& title, const QString& unit, std::vector<double> wavelengths_nm,
                                std::vector<double> values) {
    m_title = title;
    m_unit = unit;
    m_wavelengths_nm = std::move(wavelengths_nm);
    m_values = std::move(values);
    update();
}

void SpectrumChart::clear() {
    m_title.clear();
    m_values.clear();
    m_wavelengths_nm.clear();
    update();
}

QString SpectrumChart::valueAxisTitle() const {
    return m_unit.isEmpty() || m_unit == "1" ? m_title : m_title + " (" + m_unit + ")";
}

void SpectrumChart::paintEvent(QPaintEvent* /*event*/) {
    m_value_title_rect = {};
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    const QFontMetrics fm = p.fontMetrics();
    const QColor ink = palette().color(QPalette::Text);
    if (m_values.empty()) {
        p.setPen(palette().color(QPalette::PlaceholderText));
        p.drawText(rect(), Qt::AlignCenter, tr("No spectrum selected"));
        return;
    }
    const bool constant = m_values.size() == 1;
    // The x range: the visible range, widened to the samples.
    double x0 = kVisibleMinNm;
    double x1 = kVisibleMaxNm;
    if (!constant) {
        x0 = std::min(x0, m_wavelengths_nm.front());
        x1 = std::max(x1, m_wavelengths_nm.back());
    }
    auto [lo_it, hi_it] = std::minmax_element(m_values.begin(), m_values.end());
    double y0 = std::min(0.0, *lo_it);
    double y1 = *hi_it;
    if (!(y1 > y0)) y1 = y0 + (y0 == 0.0 ? 1.0 : std::abs(y0));
    y1 += (y1 - y0) * 0.05;
    const std::vector<double> yticks = niceTicks(y0, y1, 4);
    const std::vector<double> xticks = niceTicks(x0, x1, 5);

    int label_width = 0;
    for (const double t : yticks)
        label_width = std::max(label_width, fm.horizontalAdvance(QString::number(t)));
    // Left of the tick numbers, the value axis' label turned upright.
    const double title_band = fm.height() + 4.0;
    const QRectF plot(title_band + label_width + 10.0, fm.height() + 8.0,
                      width() - title_band - label_width - 20.0, height() - 2.0 * fm.height() - 20.0);
    if (plot.width() < 20 || plot.height() < 20) return;
    const auto X = [&](double x) { return plot.left() + (x - x0) / (x1 - x0) * plot.width(); };
    const auto Y = [&](double y) { return plot.bottom() - (y - y0) / (y1 - y0) * plot.height(); };

    p.setPen(ink);
    const QString heading = valueAxisTitle();
    p.drawText(QRectF(0, 2, width(), fm.height()), Qt::AlignHCenter, heading);
    // Elided to the axis' length, so that it is never cut off.
    const QString upright = fm.elidedText(heading, Qt::ElideRight, static_cast<int>(plot.height()));
    const int upright_width = fm.horizontalAdvance(upright);
    p.save();
    p.translate(2.0, plot.center().y() + upright_width / 2.0);
    p.rotate(-90.0);
    p.drawText(QRectF(0, 0, upright_width, fm.height()), Qt::AlignLeft | Qt::AlignTop, upright);
    p.restore();
    m_value_title_rect =
        QRectF(2.0, plot.center().y() - upright_width / 2.0, fm.height(), upright_width).toAlignedRect();
    QPen grid(palette().color(QPalette::Mid));
    grid.setStyle(Qt::DotLine);
    for (const double t : yticks) {
        if (t < y0 || t > y1) continue;
        p.setPen(grid);
        p.drawLine(QPointF(plot.left(), Y(t)), QPointF(plot.right(), Y(t)));
        p.setPen(ink);
        p.drawText(QRectF(title_band, Y(t) - fm.height() / 2.0, label_width + 6.0, fm.height()),
                   Qt::AlignRight | Qt::AlignVCenter, QString::number(t));
    }
    for (const double t : xticks) {
        p.setPen(grid);
        p.drawLine(QPointF(X(t), plot.top()), QPointF(X(t), plot.bottom()));
        p.setPen(ink);
        p.drawText(QRectF(X(t) - 30, plot.bottom() + 2, 60, fm.height()), Qt::AlignHCenter,
                   QString::number(t));
    }
    p.drawText(QRectF(plot.left(), height() - fm.height() - 2.0, plot.width(), fm.height()), Qt::AlignHCenter,
               tr("wavelength (nm)"));
    p.setPen(ink);
    p.drawRect(plot);

    QPen curve(QColor(31, 119, 180));
    curve.setWidthF(2.0);
    p.setPen(curve);
    if (constant) {
        p.drawLine(QPointF(X(x0), Y(m_values.front())), QPointF(X(x1), Y(m_values.front())));
        return;
    }
    QPainterPath path;
    // Held constant beyond the ends, as Spectrum evaluates it.
    path.moveTo(X(x0), Y(m_values.front()));
    for (std::size_t i = 0; i < m_values.size(); ++i) path.lineTo(X(m_wavelengths_nm[i]), Y(m_values[i]));
    path.lineTo(X(x1), Y(m_values.back()));
    p.drawPath(path);
    if (m_values.size() <= 100) {
        p.setBrush(curve.color());
        for (std::size_t i = 0; i < m_values.size(); ++i)
            p.drawEllipse(QPointF(X(m_wavelengths_nm[i]), Y(m_values[i])), 2.0, 2.0);
    }
}

}  // namespace paintlab::gui
