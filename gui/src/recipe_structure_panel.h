#pragma once
// The top of the recipe editor: the recipe's layers as a list (top coat
// first, as the recipe orders them) with add, remove, move up / down and
// rename, and the selected layer's components as a table (name, kind,
// volume fraction) with remove and move up / down. Components are added
// from the Ingredients dock, which adds to the layer selected here
// (RecipeDocument::selectedLayer).
//
// Every edit is one undo step (ReplaceRecipeCommand: the whole recipe before
// and after), made by recipe_structure.h and checked with the engine's
// validation first: a refused edit shows a message naming the field and
// leaves the recipe as it was.

#include "recipe_document.h"
#include "recipe_structure.h"

#include <QString>
#include <QWidget>

#include <functional>

class QGroupBox;
class QLabel;
class QListWidget;
class QTableWidget;
class QToolButton;

namespace paintlab::gui {

class RecipeStructurePanel : public QWidget {
    Q_OBJECT
public:
    explicit RecipeStructurePanel(RecipeDocument* document, QWidget* parent = nullptr);

    int selectedLayer() const { return m_layer; }
    void selectLayer(int layer);
    int selectedComponent() const { return m_component; }  // -1: none
    void selectComponent(int component);

    // The edits of the buttons, on the selected layer or component; false
    // (and the reason in message()) when refused or when nothing is selected.
    bool addLayer();  // a clear lacquer above the selected layer (on top if none)
    bool removeLayer();
    bool moveLayer(int delta);  // -1: up (towards the top coat), +1: down
    bool renameLayer(const QString& name);
    bool removeComponent();
    bool moveComponent(int delta);

    QString message() const;  // the last refusal, empty after an accepted edit
    QListWidget* layerList() const { return m_layers; }
    QTableWidget* componentTable() const { return m_components; }

private:
    // Makes the edit, checks it and pushes it; selects (layer, component) after it.
    bool apply(const std::function<StructureEdit(const Recipe&)>& make, int layer, int component);
    void refresh();
    void fillComponents();
    void updateButtons();
    QToolButton* button(const QString& name, const QString& text, const QString& tip);

    RecipeDocument* m_document;
    int m_layer = 0;
    int m_component = -1;
    bool m_filling = false;
    QListWidget* m_layers = nullptr;
    QGroupBox* m_component_box = nullptr;
    QTableWidget* m_components = nullptr;
    QToolButton* m_add_layer = nullptr;
    QToolButton* m_remove_layer = nullptr;
    QToolButton* m_layer_up = nullptr;
    QToolButton* m_layer_down = nullptr;
    QToolButton* m_rename_layer = nullptr;
    QToolButton* m_remove_component = nullptr;
    QToolButton* m_component_up = nullptr;
    QToolButton* m_component_down = nullptr;
    QLabel* m_message = nullptr;
};

}  // namespace paintlab::gui
