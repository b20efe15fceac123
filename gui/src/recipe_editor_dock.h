#pragma once
// The recipe editor: every scalar parameter of the recipe (recipe_parameters.h)
// as a spin box with its unit and a slider over its typical range, grouped by
// layer and component. Every change is an undoable command; dragging a slider
// marks its edits interactive (the render dock then uses the preview preset)
// and releasing it ends the drag with a final, non-interactive edit.

#include "recipe_document.h"
#include "recipe_parameters.h"

#include <QDockWidget>

#include <string_view>
#include <vector>

class QDoubleSpinBox;
class QSlider;
class QVBoxLayout;

namespace paintlab::gui {

class RecipeEditorDock : public QDockWidget {
    Q_OBJECT
public:
    explicit RecipeEditorDock(RecipeDocument* document, QWidget* parent = nullptr);

    // The slider of the first parameter with this declaration key (for tests), or nullptr.
    QSlider* sliderFor(std::string_view key) const;

private:
    struct Row {
        ParameterRef ref;
        SliderRange range;
        QDoubleSpinBox* spin = nullptr;
        QSlider* slider = nullptr;
    };
    void rebuild();
    bool structureChanged() const;
    void refreshValues();
    void edit(const Row& row, double value, bool interactive);
    static constexpr int kSliderSteps = 1000;

    RecipeDocument* m_document;
    QWidget* m_form = nullptr;
    QVBoxLayout* m_layout = nullptr;
    std::vector<Row> m_rows;
};

}  // namespace paintlab::gui
