#pragma once
// A "Depth profile..." button in a component's group of the recipe editor
// that opens that component's depth-profile editor below it (and closes it
// again). The editor is made on first use: most recipes are edited without it.

#include "recipe_document.h"

#include <QWidget>

class QToolButton;

namespace paintlab::gui {

class DepthProfileEditor;

class DepthProfileSection : public QWidget {
    Q_OBJECT
public:
    DepthProfileSection(RecipeDocument* document, int layer, int component, QWidget* parent = nullptr);

    int layer() const { return m_layer; }
    int component() const { return m_component; }
    bool isOpen() const;
    void setOpen(bool open);
    QToolButton* button() const { return m_button; }
    DepthProfileEditor* editor() const { return m_editor; }  // nullptr until first opened

private:
    RecipeDocument* m_document;
    int m_layer;
    int m_component;
    QToolButton* m_button = nullptr;
    DepthProfileEditor* m_editor = nullptr;
};

}  // namespace paintlab::gui
