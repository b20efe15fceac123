#pragma once
// The main window's layout (issue 27, items 4-6): the relit scene is the
// central widget and the docks sit around it, sized for the window's size;
// View > Reset layout puts them back; the layout (window geometry, every
// dock's place and size) persists in QSettings under a version number, so a
// state saved by an older arrangement of the docks is ignored.
//
// Default, wide window (at least kWideLayoutWidth): the recipe list above the
// recipe editor (the ingredients a tab beside it) on the left, the accuracy
// verdict (the versions and the Match dock tabs beside it) on the right, the plots (and the
// in-plane plot, a tab beside them) below the scene and the right column.
// Narrower (a laptop's 1024 x 700 or 1366 x 768): the accuracy, versions and match
// become tabs of the bottom area too, so the scene keeps most of the width.

#include <QByteArray>

class QDockWidget;
class QMainWindow;

namespace paintlab::gui {

// The dock arrangement's version, stored with the state: bump it when docks
// are added, removed or moved to other areas by default.
inline constexpr int kLayoutVersion = 3;  // 3: the Match dock
inline constexpr int kWideLayoutWidth = 1600;

struct LayoutDocks {
    QDockWidget* recipes = nullptr;
    QDockWidget* editor = nullptr;
    QDockWidget* ingredients = nullptr;
    QDockWidget* accuracy = nullptr;
    QDockWidget* versions = nullptr;
    QDockWidget* match = nullptr;  // tabbed after the versions
    QDockWidget* plots = nullptr;
    QDockWidget* inplane = nullptr;
};

// Puts each dock's content that has no scroll area of its own into one
// (frameless, resizing with the dock), so that no dock asks for more room
// than a small screen has: what does not fit scrolls. Once, after the docks are made.
void makeDocksScrollable(const LayoutDocks& docks);

// Docks every dock (none floating or hidden) where the default puts it, sized for the window's size.
void applyDefaultLayout(QMainWindow& window, const LayoutDocks& docks);
// The window's geometry and layout from QSettings; the default layout if none was saved, or one of another
// version.
void restoreLayout(QMainWindow& window, const LayoutDocks& docks);
// Writes the window's geometry and layout (called when it closes).
void saveLayout(const QMainWindow& window);

}  // namespace paintlab::gui
