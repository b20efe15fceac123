#pragma once
// Ctrl+Z / Ctrl+Shift+Z (Ctrl+Y) undo and redo the recipe's edits from any
// focus in the main window. A spin box or line edit claims the keys for its
// own text undo (a ShortcutOverride it accepts), so Edit > Undo never fired
// while a number field had focus. This filter, installed on the application,
// refuses that claim for the fields of one window (its floating docks
// included), so the window's Undo and Redo actions run: every committed value
// is one step of the document's undo stack, and the field shows the value
// the undo restored (text typed and not yet committed is dropped).
// Fields of other windows (a dialog's text box) keep their own undo.

#include <QObject>

class QWidget;

namespace paintlab::gui {

class UndoShortcutFilter : public QObject {
    Q_OBJECT
public:
    // window: the fields of this window (and its children's windows) are filtered.
    explicit UndoShortcutFilter(QWidget* window);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    QWidget* m_window;
};

}  // namespace paintlab::gui
