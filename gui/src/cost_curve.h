#pragma once
// The best cost of a running fit against the model evaluations, on a log
// scale: a glance tells whether the fit still improves or has settled.

#include <QWidget>

#include <vector>

namespace paintlab::gui {

class CostCurve : public QWidget {
    Q_OBJECT
public:
    explicit CostCurve(QWidget* parent = nullptr);

    void clear();
    void add(long evaluations, double best_cost);
    std::size_t points() const { return m_points.size(); }
    QSize sizeHint() const override { return {240, 70}; }
    QSize minimumSizeHint() const override { return {80, 40}; }

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    struct Point {
        long evaluations;
        double cost;
    };
    std::vector<Point> m_points;
};

}  // namespace paintlab::gui
