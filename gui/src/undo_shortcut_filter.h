#pragma once
// Ctrl+Z / Ctrl+Shift+Z (Ctrl+Y) undo and redo the recipe's edits from any
// focus in the main window. A spin box or line edit claims the keys for its
// own text undo (a ShortcutOverride it accepts), so Edit > Undo never fired
// while a number field had focus. This filter, installed on the application,
// refuses that claim so that the window's Undo and Redo actions run (every
// committed value is one step of the document's undo stack, and the field
// shows the value the undo restored; text typed and not yet committed is
// dropped) for
// - every spin box of the window (its floating docks included): a number
//   has no text history worth keeping;
// - the line edits of the recipe editor (a depth-profile node's fields),
//   whose values are recipe edits.
// Other text fields (the ingredient search and editor) and the fields of
// other windows (a dialog's text box) keep their own undo.

#include <QObject>

class QWidget;

namespace paintlab::gui {

class UndoShortcutFilter : public QObject {
    Q_OBJECT
public:
    // window: its spin boxes are filtered (floating docks included);
    // recipe_editor: its line edits too.
    UndoShortcutFilter(QWidget* window, QWidget* recipe_editor);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    QWidget* m_window;
    QWidget* m_recipe_editor;
};

}  // namespace paintlab::gui
