#include "comparison_image.h"

#include <QFont>
#include <QFontMetrics>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

QImage splitImage(const QImage& left, const QImage& right, int column) {
    if (left.isNull() || right.isNull() || left.size() != right.size()) return {};
    const QImage a = left.convertToFormat(QImage::Format_RGB888);
    const QImage b = right.convertToFormat(QImage::Format_RGB888);
    QImage out = a.copy();
    column = std::clamp(column, 0, a.width());
    const auto left_bytes = static_cast<std::size_t>(column) * 3;
    const auto right_bytes = static_cast<std::size_t>(a.width() - column) * 3;
    for (int y = 0; y < a.height(); ++y)
        std::copy_n(b.constScanLine(y) + left_bytes, right_bytes, out.scanLine(y) + left_bytes);
    return out;
}

QImage sideBySideImage(const QImage& left, const QImage& right) {
    const int width = left.width() + kSideBySideGap + right.width();
    const int height = std::max(left.height(), right.height());
    if (width <= kSideBySideGap || height == 0) return {};
    QImage out(width, height, QImage::Format_RGB888);
    out.fill(QColor(40, 40, 40));
    QPainter painter(&out);
    painter.setCompositionMode(QPainter::CompositionMode_Source);  // copies, never blends
    if (!left.isNull()) painter.drawImage(0, 0, left);
    if (!right.isNull()) painter.drawImage(left.width() + kSideBySideGap, 0, right);
    return out;
}

int splitColumn(int width, double fraction) {
    return std::clamp(static_cast<int>(std::lround(fraction * width)), 0, width);
}

QImage captionedImage(const QImage& pixels, const QString& left_label, const QString& right_label,
                      int divider_column) {
    if (pixels.isNull()) return {};
    QFont font;
    font.setPixelSize(std::clamp(pixels.height() / 24, 11, 28));
    const int strip = QFontMetrics(font).height() + 6;
    QImage out(pixels.width(), pixels.height() + strip, QImage::Format_RGB888);
    out.fill(QColor(40, 40, 40));
    QPainter painter(&out);
    painter.drawImage(0, strip, pixels);
    painter.setFont(font);
    painter.setPen(Qt::white);
    const QRect text(4, 0, pixels.width() - 8, strip);
    // Each label keeps to its half, shortened at the front (the version at the end stays).
    const QFontMetrics metrics(font);
    const int half = std::max(20, pixels.width() / 2 - 8);
    painter.drawText(text, Qt::AlignLeft | Qt::AlignVCenter,
                     metrics.elidedText(left_label, Qt::ElideLeft, half));
    painter.drawText(text, Qt::AlignRight | Qt::AlignVCenter,
                     metrics.elidedText(right_label, Qt::ElideLeft, half));
    if (divider_column >= 0) painter.fillRect(divider_column - 1, strip / 2, 2, strip - strip / 2, Qt::white);
    return out;
}

}  // namespace paintlab::gui
