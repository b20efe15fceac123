#pragma once
// The depth-profile chart with draggable nodes, drawn with QPainter: relative
// concentration weight w against depth in the layer (left = top of the layer,
// right = its bottom, the axis in the layer's µm). It does not change the
// profile itself: it proposes edits by signal and shows what it is given
// (DepthProfileEditor checks each proposal and sets the recipe's profile back),
// so what it draws is always what the recipe holds.
//
// Mouse: press a node and drag it (end nodes move only in weight, inner nodes
// stay between their neighbours); double-click an empty place to add a node;
// right-click a node, or select it and press Delete, to remove it (not the end nodes).

#include "paintlab/engine/recipe.h"

#include <QPointF>
#include <QRectF>
#include <QString>
#include <QWidget>

#include <cstddef>

namespace paintlab::gui {

class DepthProfilePlot : public QWidget {
    Q_OBJECT
public:
    explicit DepthProfilePlot(QWidget* parent = nullptr);

    // stored: false when the component has no profile and `profile` is the
    // implicit uniform one (drawn dashed). A drag in progress continues if
    // the node count is unchanged.
    void setProfile(const DepthProfile& profile, bool stored);
    void setThicknessUm(double thickness_um);
    const DepthProfile& profile() const { return m_profile; }
    int selectedNode() const { return m_selected; }  // -1: none
    void selectNode(int node);

    // Where node `node` is drawn, in widget coordinates (the tests press there).
    QPointF nodePosition(std::size_t node) const;
    // The relative depth (x) and weight (y) under a widget point, not clipped.
    QPointF valueAt(QPointF point) const;
    double weightAxisMax() const { return m_axis_max; }
    QString depthAxisTitle() const;

    QSize sizeHint() const override { return {420, 240}; }
    QSize minimumSizeHint() const override { return {260, 160}; }

signals:
    void nodeDragged(const paintlab::DepthProfile& profile);   // the held node moved
    void dragReleased(const paintlab::DepthProfile& profile);  // let go after moving it
    void edited(const paintlab::DepthProfile& profile);        // a node added or removed
    void refused(const QString& reason);                       // an edit that cannot be made
    void selectionChanged(int node);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    QRectF plotRect() const;
    int nodeAt(QPointF point) const;  // the node within reach of the point, or -1
    void removeNode(int node);
    void updateAxis();

    DepthProfile m_profile;
    bool m_stored = false;
    double m_thickness_um = 0.0;
    double m_axis_max = 1.5;  // held while dragging so the scale does not move under the cursor
    int m_selected = -1;
    int m_dragged = -1;
    bool m_moved = false;
};

}  // namespace paintlab::gui
