#include "undo_shortcut_filter.h"

#include <QAbstractSpinBox>
#include <QDockWidget>
#include <QKeyEvent>
#include <QLineEdit>
#include <QWidget>

namespace paintlab::gui {

UndoShortcutFilter::UndoShortcutFilter(QWidget* window, QWidget* recipe_editor)
    : QObject(window), m_window(window), m_recipe_editor(recipe_editor) {}

bool UndoShortcutFilter::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() != QEvent::ShortcutOverride) return false;
    const auto* key = static_cast<QKeyEvent*>(event);
    if (!key->matches(QKeySequence::Undo) && !key->matches(QKeySequence::Redo)) return false;
    auto* field = qobject_cast<QWidget*>(watched);
    if (field == nullptr) return false;
    // A spin box's own line edit counts as the spin box.
    if (auto* spin = qobject_cast<QAbstractSpinBox*>(field->parentWidget())) field = spin;
    const bool number = qobject_cast<QAbstractSpinBox*>(field) != nullptr;
    if (!number && (qobject_cast<QLineEdit*>(field) == nullptr || !m_recipe_editor->isAncestorOf(field)))
        return false;
    // Only this window's fields, a floating dock's included; a dialog of the
    // window (its own window) keeps its fields' undo.
    for (const QWidget* w = field; w != nullptr; w = w->parentWidget()) {
        if (w == m_window) {
            event->ignore();  // not claimed: the shortcut (Edit > Undo / Redo) runs
            return true;
        }
        if (w->isWindow() && qobject_cast<const QDockWidget*>(w) == nullptr) return false;
    }
    return false;
}

}  // namespace paintlab::gui
