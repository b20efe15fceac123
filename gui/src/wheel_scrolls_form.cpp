#include "wheel_scrolls_form.h"

#include <QEvent>
#include <QWidget>

namespace paintlab::gui {

namespace {

class WheelWithoutFocusPassesOn : public QObject {
public:
    using QObject::QObject;

protected:
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() != QEvent::Wheel) return false;
        const auto* field = qobject_cast<QWidget*>(watched);
        if (field == nullptr || field->hasFocus()) return false;
        // Filtered and not accepted: QApplication offers the event to the
        // parent widgets in turn, and the scroll area scrolls.
        event->ignore();
        return true;
    }
};

}  // namespace

void letWheelScrollTheForm(QWidget* field) {
    field->setFocusPolicy(Qt::StrongFocus);
    field->installEventFilter(new WheelWithoutFocusPassesOn(field));
}

}  // namespace paintlab::gui
