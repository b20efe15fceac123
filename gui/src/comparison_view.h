#pragma once
// The render dock's picture: one image scaled to fit (kept in proportion),
// with a label over each side and, in split view, a vertical divider the
// user drags (left of it one recipe, right of it the other). It only shows
// what the dock composed (comparison_image.h); it computes nothing.

#include <QImage>
#include <QString>
#include <QWidget>

namespace paintlab::gui {

class ComparisonView : public QWidget {
    Q_OBJECT
public:
    explicit ComparisonView(QWidget* parent = nullptr);

    // `image`: the composition; labels: "" for none; divider_column: the
    // split column in image pixels (< 0: not a split view, no divider).
    void setPicture(const QImage& image, const QString& left_label, const QString& right_label,
                    int divider_column);
    void setPlaceholder(const QString& text);
    // Where the image is drawn in the widget (empty without an image).
    QRect imageRect() const;

signals:
    // The divider was dragged to this fraction (0..1) of the image's width.
    void dividerDragged(double fraction);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;

private:
    void dragTo(int x);

    QImage m_image;
    QString m_left;
    QString m_right;
    QString m_placeholder;
    int m_divider = -1;
    bool m_dragging = false;
};

}  // namespace paintlab::gui
