#pragma once
// The depth-profile editor of one component (a pigment or a flake): the
// chart with draggable nodes (depth_profile_plot.h), presets, a uniform
// reset that removes the profile, the selected node's depth and weight as
// text, and the profile's mean weight and peak relative concentration.
//
// Every change is one command on the document's undo stack
// (set_depth_profile_command.h); a node drag is one step, its edits marked
// interactive while the node is held (the render uses the preview preset)
// and a final edit on release. A change that would make the profile or the
// recipe invalid is refused with a message naming the field, and the
// recipe is left as it was: no invalid profile reaches it.

#include "depth_profile_edit.h"
#include "recipe_document.h"

#include <QString>
#include <QWidget>

#include <optional>

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;

namespace paintlab::gui {

class DepthProfilePlot;

class DepthProfileEditor : public QWidget {
    Q_OBJECT
public:
    // The component `component` of layer `layer` (indices into the document's recipe).
    DepthProfileEditor(RecipeDocument* document, int layer, int component, QWidget* parent = nullptr);

    // One undoable edit to this profile (nullopt: uniform, no profile), if it
    // is valid; otherwise the message says why and the recipe is unchanged.
    bool apply(const std::optional<DepthProfile>& profile);
    bool applyPreset(DepthProfilePreset preset);

    DepthProfilePlot* plot() const { return m_plot; }
    QString message() const;     // the last refusal, empty after an accepted edit
    QString statistics() const;  // "mean weight 1.5 · peak relative concentration 2 ×"

private:
    bool propose(const std::optional<DepthProfile>& profile, int drag, bool interactive);
    void refuse(const QString& reason);
    void refresh();
    void showNode(int node);
    void editNode(bool depth_field);
    const std::optional<DepthProfile>* stored() const;

    RecipeDocument* m_document;
    int m_layer;
    int m_component;
    int m_drag = 0;  // the drag in progress (0: none)
    bool m_drag_pushed = false;
    QLabel* m_title = nullptr;
    DepthProfilePlot* m_plot = nullptr;
    QComboBox* m_presets = nullptr;
    QPushButton* m_uniform = nullptr;
    QLabel* m_node = nullptr;
    QLineEdit* m_depth = nullptr;
    QLineEdit* m_weight = nullptr;
    QLabel* m_statistics = nullptr;
    QLabel* m_message = nullptr;
};

}  // namespace paintlab::gui
