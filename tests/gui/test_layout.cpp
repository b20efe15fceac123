// A layout that fits the screen it is on (issue 27, items 4-6): at 1024 x
// 768's laptop cousin 1024 x 700, at 1366 x 768 and at 1920 x 1080 the main
// window takes the size asked for, and walking its widget tree finds
//  - every visible widget inside its parent (a widget larger than the room
//    its parent has is drawn over its neighbours or cut off), except the
//    content of a scroll area's viewport, which may be larger and scrolls;
//  - no overlap between the window's regions (menu bar, central view, each
//    visible docked dock widget, status bar), all inside the window;
//  - no overlap between two visible leaf widgets (no visible child) of
//    different regions, each taken as its global rectangle clipped by its
//    ancestors' (what can be seen of it); widgets of one region may stack
//    (a scroll area's content under its scroll bars), which the first rule covers;
//  - the status bar shown, the relit scene the largest part of the window
//    (at least half its width), the recipe list showing its five recipes;
// no dock scrolling sideways, the ingredient list showing 8 rows;
// and a screenshot of each size against its baseline. View > Reset layout
// brings back the default after docks were moved, floated and closed; the
// layout persists through QSettings, and a state saved by an older layout
// (another version number) is ignored.

#include "gui_test_main.h"
#include "screenshot_baseline.h"
#include "workstation_fixture.h"

#include "author_setting.h"
#include "main_window.h"
#include "raymap_resolution.h"
#include "recipe_editor_dock.h"
#include "render_dock.h"

#include <QAbstractItemView>
#include <QAbstractScrollArea>
#include <QAction>
#include <QDockWidget>
#include <QListWidget>
#include <QMenuBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>

#include <memory>
#include <vector>

using paintlab::gui::MainWindow;
using paintlab::test::kGuiWaitMs;

namespace {

const QString kPearl = QStringLiteral("Blue pearl over black (two layers)");

QRect globalRect(const QWidget* w) { return {w->mapToGlobal(QPoint(0, 0)), w->size()}; }

QString describe(const QWidget* w) {
    return QStringLiteral("%1 '%2' at %3,%4 %5x%6")
        .arg(QString::fromLatin1(w->metaObject()->className()), w->objectName())
        .arg(globalRect(w).x())
        .arg(globalRect(w).y())
        .arg(w->width())
        .arg(w->height());
}

bool inScrollViewport(const QWidget* w) {
    const QWidget* parent = w->parentWidget();
    if (parent == nullptr) return false;
    const auto* area = qobject_cast<const QAbstractScrollArea*>(parent->parentWidget());
    return area != nullptr && area->viewport() == parent;
}

struct Leaf {
    const QWidget* widget;
    QRect clipped;  // global, clipped by every ancestor
    int region;
};

// Walks `w` (visible, not a window of its own): parent containment, leaves.
void walk(const QWidget* w, const QRect& clip, int region, QStringList& errors, std::vector<Leaf>& leaves) {
    bool has_visible_child = false;
    for (const QObject* object : w->children()) {
        const auto* child = qobject_cast<const QWidget*>(object);
        if (child == nullptr || child->isWindow() || !child->isVisible()) continue;
        has_visible_child = true;
        if (!inScrollViewport(child) && !QRect(QPoint(0, 0), w->size()).contains(child->geometry()))
            errors << QStringLiteral("%1 exceeds its parent %2").arg(describe(child), describe(w));
        walk(child, clip.intersected(globalRect(child)), region, errors, leaves);
    }
    if (!has_visible_child && !clip.isEmpty()) leaves.push_back({w, clip, region});
}

}  // namespace

class LayoutTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void fitsTheScreen_data();
    void fitsTheScreen();
    void enlargingAndShrinkingAgainKeepsItTidy();
    void resetLayoutBringsBackTheDefault();
    void layoutPersistsAndAnOldOneIsIgnored();
    void rayMapResolutionFollowsTheViewWithinTheBudget();
    void cleanupTestCase();

private:
    std::unique_ptr<MainWindow> openWindow(bool scene);
    // The layout errors of the window as it is now (empty: none).
    QStringList layoutErrors();
    void resizeTo(QSize size);
    QTemporaryDir m_dir;
    QString m_scene;
    std::unique_ptr<MainWindow> m_window;
};

std::unique_ptr<MainWindow> LayoutTest::openWindow(bool scene) {
    paintlab::gui::WorkstationOptions options;
    options.database = (m_dir.path() + "/lab.db").toStdString();
    options.scene = m_scene.toStdString();
    options.open_scene = scene;
    options.raymap_follows_view = false;  // the tiny scene as it is: the test stays fast
    options.refine_ray_map = false;       // screenshots of one fixed map, not of a map refining meanwhile
    auto window = std::make_unique<MainWindow>(options);
    window->show();
    if (!QTest::qWaitForWindowExposed(window.get())) return nullptr;
    return window;
}

void LayoutTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    paintlab::test::prepareTestUser(m_dir.path());
    m_scene = paintlab::test::writeTinyDemoScene(m_dir.path());
    m_window = openWindow(true);
    QVERIFY(m_window != nullptr);
    QVERIFY(m_window->selectRecipe(kPearl));
    QTRY_VERIFY_WITH_TIMEOUT(!m_window->renderDock()->image().isNull() && m_window->scheduler()->idle(),
                             kGuiWaitMs);
}

void LayoutTest::cleanupTestCase() { m_window.reset(); }

void LayoutTest::resizeTo(QSize size) {
    m_window->resize(size);
    if (m_window->minimumSizeHint().width() > size.width() ||
        m_window->minimumSizeHint().height() > size.height()) {
        // Which part asks for more room than there is.
        qInfo("window minimum %dx%d", m_window->minimumSizeHint().width(),
              m_window->minimumSizeHint().height());
        for (const QWidget* w : m_window->findChildren<QWidget*>(Qt::FindDirectChildrenOnly))
            if (w->isVisible())
                qInfo("  %s: minimum %dx%d", qPrintable(describe(w)), w->minimumSizeHint().width(),
                      w->minimumSizeHint().height());
    }
    // The window manager-less X server applies the size at once; the docks'
    // layout follows in the next events.
    QTRY_COMPARE_WITH_TIMEOUT(m_window->size(), size, 5000);
    QTest::qWait(300);
}

QStringList LayoutTest::layoutErrors() {
    QStringList errors;
    const QRect window = globalRect(m_window.get());
    // The regions: menu bar, central view, docked dock widgets, status bar.
    std::vector<const QWidget*> regions{m_window->menuBar(), m_window->centralWidget(),
                                        m_window->statusBar()};
    for (const QDockWidget* dock : m_window->findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly))
        // A dock behind another's tab is "visible" but moved out of sight.
        if (dock->isVisible() && !dock->isFloating() && !dock->visibleRegion().isEmpty())
            regions.push_back(dock);
    if (!m_window->statusBar()->isVisible() || m_window->statusBar()->height() <= 0)
        errors << QStringLiteral("the status bar is not shown");
    std::vector<Leaf> leaves;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const QRect r = globalRect(regions[i]);
        if (!window.contains(r)) errors << describe(regions[i]) + " is not inside the window";
        for (std::size_t j = 0; j < i; ++j)
            if (r.intersects(globalRect(regions[j])))
                errors << QStringLiteral("%1 overlaps %2").arg(describe(regions[i]), describe(regions[j]));
        walk(regions[i], r.intersected(window), static_cast<int>(i), errors, leaves);
    }
    for (std::size_t i = 0; i < leaves.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (leaves[i].region != leaves[j].region && leaves[i].clipped.intersects(leaves[j].clipped))
                errors << QStringLiteral("%1 overlaps %2")
                              .arg(describe(leaves[i].widget), describe(leaves[j].widget));
    return errors;
}

void LayoutTest::fitsTheScreen_data() {
    QTest::addColumn<QSize>("size");
    QTest::newRow("1024x700") << QSize(1024, 700);
    QTest::newRow("1366x768") << QSize(1366, 768);
    QTest::newRow("1500x988") << QSize(1500, 988);  // where the issue saw the editor scroll sideways
    QTest::newRow("1920x1080") << QSize(1920, 1080);
}

void LayoutTest::fitsTheScreen() {
    QFETCH(QSize, size);
    // The layout a first start gives at this size.
    QAction* reset = m_window->findChild<QAction*>(QStringLiteral("reset_layout_action"));
    resizeTo(size);
    if (QTest::currentTestFailed()) return;
    if (reset != nullptr) reset->trigger();
    QTest::qWait(300);
    const QStringList errors = layoutErrors();
    for (const QString& e : errors) qInfo("%s", qPrintable(e));
    QVERIFY2(errors.isEmpty(),
             qPrintable(
                 QStringLiteral("%1 layout errors, the first: %2").arg(errors.size()).arg(errors.value(0))));
    // The relit scene is the centrepiece.
    const QWidget* view = m_window->findChild<QWidget*>(QStringLiteral("render_view"));
    QVERIFY(view != nullptr && view->isVisible());
    QVERIFY2(view->width() * 2 >= size.width(), qPrintable(describe(view)));
    // The recipe list shows the five demo recipes without scrolling.
    QListWidget* list = m_window->recipeList();
    QVERIFY(list->isVisible());
    QVERIFY2(list->viewport()->height() >= 5 * list->sizeHintForRow(0),
             qPrintable(QStringLiteral("recipe list %1 px high, rows %2 px")
                            .arg(list->viewport()->height())
                            .arg(list->sizeHintForRow(0))));
    // No docked dock scrolls sideways: the recipe editor's rows, the
    // ingredients, the plots' buttons fit their columns (each dock's own
    // scroll area; a table's columns may scroll inside the table).
    for (QDockWidget* dock : m_window->findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly)) {
        if (dock->isFloating()) continue;
        dock->raise();  // the docks behind a tab too
        QTest::qWait(50);
        auto* scroll = qobject_cast<QScrollArea*>(dock->widget());
        if (scroll != nullptr && scroll->horizontalScrollBar()->isVisible())
            for (const QWidget* w : scroll->widget()->findChildren<QWidget*>())
                if (w->isVisible() && w->minimumSizeHint().width() > scroll->viewport()->width() - 30)
                    qInfo("wide in %s: %s, minimum width %d", qPrintable(dock->objectName()),
                          qPrintable(describe(w)), w->minimumSizeHint().width());
        if (scroll != nullptr)
            QVERIFY2(!scroll->horizontalScrollBar()->isVisible(),
                     qPrintable(QStringLiteral("%1 scrolls sideways: its content needs %2 px, it has %3")
                                    .arg(dock->objectName())
                                    .arg(scroll->widget()->minimumSizeHint().width())
                                    .arg(scroll->viewport()->width())));
    }
    // The ingredient list shows a useful number of rows (the issue saw 3.5 at 1500 x 988).
    auto* ingredients = m_window->findChild<QAbstractItemView*>(QStringLiteral("ingredient_list"));
    QVERIFY(ingredients != nullptr);
    m_window->findChild<QDockWidget*>(QStringLiteral("ingredients"))->raise();
    QTest::qWait(50);
    QVERIFY2(ingredients->viewport()->height() >= 8 * ingredients->sizeHintForRow(0),
             qPrintable(QStringLiteral("ingredient list %1 px high, rows %2 px")
                            .arg(ingredients->viewport()->height())
                            .arg(ingredients->sizeHintForRow(0))));
    m_window->findChild<QAction*>(QStringLiteral("reset_layout_action"))
        ->trigger();  // the default tabs in front
    QTest::qWait(300);

    // The whole window against its baseline. Threshold: mean SSIM 0.98 as
    // the workstation's (test_workstation.cpp: deterministic layout and
    // renders, measured times masked; a blank plot there gives 0.962).
    paintlab::test::maskMeasuredTimes(*m_window);
    const auto result = paintlab::test::compareWithBaseline(
        *m_window, QStringLiteral("layout-%1x%2").arg(size.width()).arg(size.height()), 0.98);
    qInfo("%s", qPrintable(result.message));
    QVERIFY2(result.ok, qPrintable(result.message));
}

// The issue saw the overlap remain after enlarging the window again: the
// laptop's layout stretched to a large screen and back, without a reset.
void LayoutTest::enlargingAndShrinkingAgainKeepsItTidy() {
    resizeTo(QSize(1024, 700));
    m_window->findChild<QAction*>(QStringLiteral("reset_layout_action"))->trigger();
    for (const QSize size : {QSize(1920, 1080), QSize(1024, 700), QSize(1366, 768)}) {
        resizeTo(size);
        const QStringList errors = layoutErrors();
        QVERIFY2(errors.isEmpty(),
                 qPrintable(
                     QStringLiteral("%1x%2: %3").arg(size.width()).arg(size.height()).arg(errors.value(0))));
    }
}

void LayoutTest::resetLayoutBringsBackTheDefault() {
    resizeTo(QSize(1366, 768));
    QAction* reset = m_window->findChild<QAction*>(QStringLiteral("reset_layout_action"));
    QVERIFY2(reset != nullptr, "View > Reset layout");
    reset->trigger();
    QTest::qWait(300);
    const QByteArray before = m_window->saveState();
    // A technician's mess: a dock floated, one closed, one moved to the other side.
    const auto docks = m_window->findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly);
    QVERIFY(docks.size() >= 4);
    docks[0]->setFloating(true);
    docks[1]->close();
    m_window->addDockWidget(Qt::RightDockWidgetArea, docks[2]);
    QTest::qWait(300);
    QVERIFY(m_window->saveState() != before);
    reset->trigger();
    QTest::qWait(300);
    for (const QDockWidget* dock : docks) QVERIFY2(!dock->isFloating(), qPrintable(dock->objectName()));
    QCOMPARE(m_window->saveState(), before);
    QVERIFY(layoutErrors().isEmpty());
}

void LayoutTest::layoutPersistsAndAnOldOneIsIgnored() {
    resizeTo(QSize(1366, 768));
    auto recipesOf = [](MainWindow& w) { return w.findChild<QDockWidget*>(QStringLiteral("recipes")); };
    QVERIFY(recipesOf(*m_window) != nullptr);
    const int default_width = recipesOf(*m_window)->width();
    // The user widens the left column; closing the window saves the layout.
    const int widened = default_width + 60;
    m_window->resizeDocks({recipesOf(*m_window)}, {widened}, Qt::Horizontal);
    QTest::qWait(300);
    QCOMPARE(recipesOf(*m_window)->width(), widened);
    QVERIFY(m_window->close());
    m_window.reset();

    auto again = openWindow(false);
    QVERIFY(again != nullptr);
    QTest::qWait(300);
    QCOMPARE(again->size(), QSize(1366, 768));
    QCOMPARE(recipesOf(*again)->width(), widened);
    // A state saved by an older layout (version 0: the dock widgets' names
    // match, the arrangement may not) is ignored: the default comes instead.
    again->resizeDocks({recipesOf(*again)}, {widened + 40}, Qt::Horizontal);
    QTest::qWait(300);
    const QByteArray old_state = again->saveState(0);
    QVERIFY(again->close());
    again.reset();
    QSettings().setValue(QStringLiteral("window/state"), old_state);
    m_window = openWindow(false);
    QVERIFY(m_window != nullptr);
    QTest::qWait(300);
    QCOMPARE(m_window->size(), QSize(1366, 768));
    QCOMPARE(recipesOf(*m_window)->width(), default_width);
}

void LayoutTest::rayMapResolutionFollowsTheViewWithinTheBudget() {
    using paintlab::gui::PixelSize;
    using paintlab::gui::rayMapBox;
    using paintlab::gui::rayMapResolution;
    const PixelSize demo{480, 270};  // the demo scene's camera, 16:9
    // A laptop's view (1024 x 700 layout): 704 x 384 box, the camera's 16:9 inside it.
    QVERIFY((rayMapBox({710, 390}) == PixelSize{704, 384}));
    QVERIFY((rayMapResolution({704, 384}, demo) == PixelSize{682, 384}));
    // A large view: the budget, 960 x 540, at the camera's aspect.
    const PixelSize big = rayMapResolution(rayMapBox({1500, 1000}), demo);
    QVERIFY(static_cast<std::int64_t>(big.width) * big.height <= paintlab::gui::kMaxRayMapPixels);
    QVERIFY((big == PixelSize{960, 540}));
    // A tall view: the width limits; small views keep a usable floor.
    QVERIFY((rayMapResolution({640, 1024}, demo) == PixelSize{640, 360}));
    QVERIFY((rayMapBox({10, 10}) == PixelSize{128, 64}));
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<LayoutTest>(argc, argv, "PaintLab-test-layout");
}

#include "test_layout.moc"
