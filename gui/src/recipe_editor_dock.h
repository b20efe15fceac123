#pragma once
// The recipe editor: every scalar parameter of the recipe (recipe_parameters.h)
// as a spin box with its unit and a slider over its typical range, grouped by
// layer and component. Every change is an undoable command; dragging a slider
// marks its edits interactive (the render dock then uses the preview preset)
// and releasing it ends the drag with a final, non-interactive edit.
// Above the rows: the layer list and component table (recipe_structure_panel.h).

#include "recipe_document.h"
#include "recipe_parameters.h"

#include <QDockWidget>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

class QLabel;
class QSlider;
class QVBoxLayout;

namespace paintlab::gui {

class ParameterField;
class RecipeStructurePanel;

class RecipeEditorDock : public QDockWidget {
    Q_OBJECT
public:
    explicit RecipeEditorDock(RecipeDocument* document, QWidget* parent = nullptr);

    // The slider of the first parameter with this declaration key (for tests), or nullptr.
    QSlider* sliderFor(std::string_view key) const;
    // The message under that parameter's field (a refused or unusual value), or nullptr.
    QLabel* messageFor(std::string_view key) const;
    RecipeStructurePanel* structurePanel() const { return m_structure; }

protected:
    // Keeps the structure panel as wide as the scroll area's view.
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    struct Row {
        ParameterRef ref;
        SliderRange range;
        ParameterField* spin = nullptr;
        QSlider* slider = nullptr;
        QLabel* message = nullptr;  // under the row: what a typed value did (hidden when nothing)
    };
    // The layers' names and their components' "kind name", in recipe order:
    // what the rows' group titles show.
    using Shape = std::vector<std::pair<std::string, std::vector<std::string>>>;
    static Shape shapeOf(const Recipe& recipe);
    void rebuild();
    bool structureChanged() const;
    void refreshValues();
    void edit(const Row& row, double value, bool interactive);
    // The field's text committed (Enter, focus out): applied, refused or warned about at the field.
    void commitTyped(Row& row);
    static void showMessage(const Row& row, const QString& text, bool error);
    static constexpr int kSliderSteps = 1000;

    RecipeDocument* m_document;
    RecipeStructurePanel* m_structure = nullptr;
    Shape m_shape;  // of the recipe the rows were built for
    int m_content_margins = 0;
    QWidget* m_form = nullptr;
    QVBoxLayout* m_layout = nullptr;
    std::vector<Row> m_rows;
    int m_drag = 0;  // the number of the slider drag under way (or the last one)
};

}  // namespace paintlab::gui
