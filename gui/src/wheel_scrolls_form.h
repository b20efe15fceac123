#pragma once
// A number field or slider in a scrolling form takes the mouse wheel only
// when it has keyboard focus. Otherwise the wheel scrolls the form, as a
// technician scrolling down the recipe editor expects: a field passing under
// the pointer used to take the wheel and change its value (a basecoat went
// from 15 to 9 µm unnoticed). A click or Tab gives the field focus, and then
// the wheel steps it as before.

class QWidget;

namespace paintlab::gui {

// Sets `field`'s focus policy to Qt::StrongFocus (not wheel focus) and hands
// wheel events it gets without focus on to its parent (the form's scroll area).
void letWheelScrollTheForm(QWidget* field);

}  // namespace paintlab::gui
