#include "window_layout.h"

#include <QDockWidget>
#include <QListWidget>
#include <QMainWindow>
#include <QScrollArea>
#include <QSettings>

#include <algorithm>

namespace paintlab::gui {

namespace {

const QString kGeometryKey = QStringLiteral("window/geometry");
const QString kStateKey = QStringLiteral("window/state");

// The recipe list's height: room for `rows` rows, its frame and a little air.
int listHeight(const QDockWidget* dock, int rows) {
    const auto* list = qobject_cast<const QListWidget*>(dock->widget());
    const int row = list != nullptr && list->count() > 0 ? list->sizeHintForRow(0) : 18;
    return rows * row + 40;  // + the dock's title bar and the list's frame
}

}  // namespace

void makeDocksScrollable(const LayoutDocks& docks) {
    for (QDockWidget* dock : {docks.recipes, docks.editor, docks.ingredients, docks.accuracy, docks.versions,
                              docks.match, docks.plots, docks.inplane}) {
        QWidget* content = dock->widget();
        if (content == nullptr || qobject_cast<QAbstractScrollArea*>(content) != nullptr) continue;
        auto* scroll = new QScrollArea(dock);
        scroll->setObjectName(dock->objectName() + "_scroll");
        scroll->setFrameShape(QFrame::NoFrame);
        scroll->setWidgetResizable(true);
        scroll->setWidget(content);  // takes it from the dock
        dock->setWidget(scroll);
    }
}

void applyDefaultLayout(QMainWindow& window, const LayoutDocks& docks) {
    const int width = window.width();
    const int height = window.height();
    const bool wide = width >= kWideLayoutWidth;
    // The side columns run the window's full height; the bottom area spans the
    // scene and, on a wide window, the right column's foot too.
    window.setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
    window.setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
    window.setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    window.setCorner(Qt::BottomRightCorner, Qt::BottomDockWidgetArea);
    for (QDockWidget* dock : {docks.recipes, docks.editor, docks.ingredients, docks.accuracy, docks.versions,
                              docks.match, docks.plots, docks.inplane}) {
        dock->setFloating(false);
        window.removeDockWidget(dock);  // also out of any tab group
    }
    window.addDockWidget(Qt::LeftDockWidgetArea, docks.recipes);
    window.addDockWidget(Qt::LeftDockWidgetArea, docks.editor);
    window.tabifyDockWidget(docks.editor, docks.ingredients);
    window.addDockWidget(Qt::BottomDockWidgetArea, docks.plots);
    window.tabifyDockWidget(docks.plots, docks.inplane);
    if (wide) {
        window.addDockWidget(Qt::RightDockWidgetArea, docks.accuracy);
        window.tabifyDockWidget(docks.accuracy, docks.versions);
    } else {
        window.tabifyDockWidget(docks.inplane, docks.accuracy);
        window.tabifyDockWidget(docks.accuracy, docks.versions);
    }
    window.tabifyDockWidget(docks.versions, docks.match);
    for (QDockWidget* dock : {docks.recipes, docks.editor, docks.ingredients, docks.accuracy, docks.versions,
                              docks.match, docks.plots, docks.inplane})
        dock->show();
    docks.editor->raise();
    docks.plots->raise();
    if (wide) docks.accuracy->raise();

    // Sizes: the left column as wide as the editor's rows need (a field, a
    // slider, a unit); the bottom 38 % of the height (two button rows, tabs, a plot); the recipe list
    // with room for its demo recipes and one more.
    const int left = std::clamp(width * 24 / 100, 360, 460);
    window.resizeDocks({docks.recipes}, {left}, Qt::Horizontal);
    if (wide) window.resizeDocks({docks.accuracy}, {std::clamp(width * 23 / 100, 340, 480)}, Qt::Horizontal);
    window.resizeDocks({docks.plots}, {std::clamp(height * 38 / 100, 240, 400)}, Qt::Vertical);
    const int list = listHeight(docks.recipes, 6);
    window.resizeDocks({docks.recipes, docks.editor}, {list, std::max(200, height - list)}, Qt::Vertical);
}

void restoreLayout(QMainWindow& window, const LayoutDocks& docks) {
    const QSettings settings;
    window.restoreGeometry(settings.value(kGeometryKey).toByteArray());
    // The default first: a saved state of this version then moves and sizes
    // the docks; one of another version (or none) leaves the default.
    applyDefaultLayout(window, docks);
    window.restoreState(settings.value(kStateKey).toByteArray(), kLayoutVersion);
}

void saveLayout(const QMainWindow& window) {
    QSettings settings;
    settings.setValue(kGeometryKey, window.saveGeometry());
    settings.setValue(kStateKey, window.saveState(kLayoutVersion));
}

}  // namespace paintlab::gui
