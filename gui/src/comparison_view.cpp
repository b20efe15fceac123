#include "comparison_view.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

namespace {

constexpr int kGrabPixels = 6;  // how near the divider a press must be to drag it

}  // namespace

ComparisonView::ComparisonView(QWidget* parent) : QWidget(parent), m_placeholder(tr("No image yet")) {
    setObjectName("render_view");
    setMinimumSize(240, 135);
    setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Ignored);
    setMouseTracking(true);
}

void ComparisonView::setPicture(const QImage& image, const QString& left_label, const QString& right_label,
                                int divider_column) {
    m_image = image;
    m_left = left_label;
    m_right = right_label;
    m_divider = divider_column;
    update();
}

void ComparisonView::setPlaceholder(const QString& text) {
    m_placeholder = text;
    update();
}

QRect ComparisonView::imageRect() const {
    if (m_image.isNull()) return {};
    const QSize size = m_image.size().scaled(this->size(), Qt::KeepAspectRatio);
    return {QPoint((width() - size.width()) / 2, (height() - size.height()) / 2), size};
}

void ComparisonView::paintEvent(QPaintEvent* /*event*/) {
    QPainter painter(this);
    if (m_image.isNull()) {
        painter.drawText(rect(), Qt::AlignCenter, m_placeholder);
        return;
    }
    const QRect target = imageRect();
    painter.setRenderHint(QPainter::SmoothPixmapTransform);
    painter.drawImage(target, m_image);
    const auto x_of = [&](int column) {
        return target.left() +
               static_cast<int>(std::lround(static_cast<double>(column) * target.width() / m_image.width()));
    };
    if (m_divider >= 0) {
        const int x = x_of(m_divider);
        painter.fillRect(x - 1, target.top(), 2, target.height(), Qt::white);
        // A handle in the middle shows that the line can be dragged.
        painter.setBrush(Qt::white);
        painter.setPen(Qt::black);
        painter.drawEllipse(QPoint(x, target.center().y()), 5, 5);
    }
    // Labels on a dark band so they read on any paint.
    const QFontMetrics metrics(font());
    const auto label = [&](const QString& full, bool right) {
        if (full.isEmpty()) return;
        // Each label keeps to its half of the image, shortened at the front
        // (the version at the end stays readable).
        const QString text = metrics.elidedText(full, Qt::ElideLeft, std::max(20, target.width() / 2 - 14));
        const int w = metrics.horizontalAdvance(text) + 8;
        const QRect box(right ? target.right() - w - 3 : target.left() + 3, target.top() + 3, w,
                        metrics.height() + 4);
        painter.fillRect(box, QColor(0, 0, 0, 160));
        painter.setPen(Qt::white);
        painter.drawText(box, Qt::AlignCenter, text);
    };
    label(m_left, false);
    label(m_right, true);
}

void ComparisonView::mousePressEvent(QMouseEvent* event) {
    const QRect target = imageRect();
    if (m_divider < 0 || target.isEmpty() || event->button() != Qt::LeftButton) return;
    const int x = target.left() + m_divider * target.width() / std::max(1, m_image.width());
    const int mx = static_cast<int>(event->position().x());
    // A press anywhere on the image moves the divider there; near it, grabs it.
    m_dragging = true;
    if (std::abs(mx - x) > kGrabPixels) dragTo(mx);
}

void ComparisonView::mouseMoveEvent(QMouseEvent* event) {
    if (m_dragging) dragTo(static_cast<int>(event->position().x()));
}

void ComparisonView::mouseReleaseEvent(QMouseEvent* event) {
    if (m_dragging && event->button() == Qt::LeftButton) {
        dragTo(static_cast<int>(event->position().x()));
        m_dragging = false;
    }
}

void ComparisonView::dragTo(int x) {
    const QRect target = imageRect();
    if (target.isEmpty()) return;
    emit dividerDragged(std::clamp(static_cast<double>(x - target.left()) / target.width(), 0.0, 1.0));
}

}  // namespace paintlab::gui
