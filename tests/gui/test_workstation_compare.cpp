// The render dock's version comparison (part of test_workstation, whose
// fixture it shares: test_workstation.h): the edited recipe against a saved
// version, split and side by side, each side pixel for pixel the single
// render of its recipe, and switching the version compared.

#include "test_workstation.h"

#include "accuracy_dock.h"
#include "comparison_view.h"
#include "inplane_plot.h"
#include "plots_dock.h"
#include "recipe_editor_dock.h"
#include "render_dock.h"
#include "versions_dock.h"

#include "paintlab/database/database.h"
#include "paintlab/database/recipes.h"

#include <QImage>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>

using paintlab::test::kPearl;
using paintlab::test::kWaitMs;

// The pearl as edited (left) against its saved version 1 (right): each side
// of the split view is the single render of its recipe at the same
// settings, pixel for pixel, wherever the divider is dragged.
void WorkstationTest::splitViewHalvesEqualTheSingleRenders() {
    QVERIFY(m_window->selectRecipe(kPearl));  // version 2 (the thicker clear coat)
    QSlider* slider = m_window->editorDock()->sliderFor("volume_fraction");
    QVERIFY(slider != nullptr);
    slider->setValue(slider->value() / 2 + 5);  // an unsaved edit
    waitIdle();
    paintlab::gui::RenderDock* dock = m_window->renderDock();
    dock->setMode(paintlab::gui::CompareMode::Split);
    QVERIFY(m_window->versionsDock()->compareInRender(1));
    waitComparison();
    QVERIFY2(dock->comparisonLabel().endsWith(QStringLiteral(", version 1")),
             qPrintable(dock->comparisonLabel()));

    auto db = paintlab::db::Database::open((m_dir.path() + "/lab.db").toStdString());
    const paintlab::Recipe version1 = paintlab::db::loadRecipeVersion(db, kPearl.toStdString(), 1).recipe;
    const paintlab::Preset preset = m_window->accuracyDock()->presetFor(false);
    const QImage left = singleRender(m_window->document()->recipe(), preset).image;
    const QImage right = singleRender(version1, preset).image;
    QVERIFY(!left.isNull() && !right.isNull());
    QVERIFY(left != right);  // else the comparison below could not fail
    QVERIFY(dock->image() == left);
    QVERIFY(dock->comparisonImage() == right);

    // Dragging the divider with the mouse: from the middle to a quarter of the width.
    auto* view = dock->findChild<paintlab::gui::ComparisonView*>();
    QVERIFY(view != nullptr);
    const QRect area = view->imageRect();
    QVERIFY(!area.isEmpty());
    QTest::mousePress(view, Qt::LeftButton, {}, QPoint(area.center().x(), area.center().y()));
    QTest::mouseMove(view, QPoint(area.left() + area.width() / 4, area.center().y()));
    QTest::mouseRelease(view, Qt::LeftButton, {}, QPoint(area.left() + area.width() / 4, area.center().y()));
    QVERIFY2(std::abs(dock->splitFraction() - 0.25) < 0.05,
             qPrintable(QString::number(dock->splitFraction())));

    for (const double fraction : {dock->splitFraction(), 0.5, 0.8}) {
        dock->setSplitFraction(fraction);
        const QImage shown = dock->shownPixels().convertToFormat(QImage::Format_RGB888);
        QCOMPARE(shown.size(), left.size());
        const int column = paintlab::gui::splitColumn(left.width(), fraction);
        QVERIFY(column > 0 && column < left.width());
        QVERIFY(shown.copy(0, 0, column, shown.height()) ==
                left.convertToFormat(QImage::Format_RGB888).copy(0, 0, column, left.height()));
        QVERIFY(shown.copy(column, 0, shown.width() - column, shown.height()) ==
                right.convertToFormat(QImage::Format_RGB888)
                    .copy(column, 0, right.width() - column, right.height()));
    }
    // Saving saves what is shown: the split pixels under a caption strip.
    const QImage saved = dock->imageToSave().convertToFormat(QImage::Format_RGB888);
    const int strip = saved.height() - left.height();
    QVERIFY(strip > 0);
    QVERIFY(saved.copy(0, strip, saved.width(), left.height()) ==
            dock->shownPixels().convertToFormat(QImage::Format_RGB888));
    dock->grab().save(QStringLiteral("screenshots/render-split.png"));
}

void WorkstationTest::sideBySideShowsBoth() {
    waitComparison();
    paintlab::gui::RenderDock* dock = m_window->renderDock();
    dock->setMode(paintlab::gui::CompareMode::SideBySide);
    const QImage left = dock->image().convertToFormat(QImage::Format_RGB888);
    const QImage right = dock->comparisonImage().convertToFormat(QImage::Format_RGB888);
    const QImage shown = dock->shownPixels().convertToFormat(QImage::Format_RGB888);
    QCOMPARE(shown.width(), left.width() + paintlab::gui::kSideBySideGap + right.width());
    QCOMPARE(shown.height(), left.height());
    QVERIFY(shown.copy(0, 0, left.width(), left.height()) == left);
    QVERIFY(shown.copy(left.width() + paintlab::gui::kSideBySideGap, 0, right.width(), right.height()) ==
            right);
    QCOMPARE(dock->imageToSave().width(), shown.width());
    dock->grab().save(QStringLiteral("screenshots/render-side-by-side.png"));
    dock->setMode(paintlab::gui::CompareMode::Single);
    QVERIFY(dock->shownPixels() == dock->image());
    QVERIFY(dock->imageToSave() == dock->image());
}

// Another version picked in the Versions dock replaces the comparison: it is
// rendered (a new result from the comparison's scheduler) and labelled. The
// edited pearl (other flake concentration) is saved as version 3 first:
// version 2's thicker clear coat alone looks the same as version 1.
void WorkstationTest::switchingVersionsRendersTheOtherVersion() {
    waitComparison();
    QVERIFY(m_window->saveVersionAs(QStringLiteral("other flake concentration (GUI test)")));
    paintlab::gui::RenderDock* dock = m_window->renderDock();
    const QImage version1 = dock->comparisonImage();
    QSignalSpy rendered(m_window->comparisonScheduler(), &paintlab::gui::RenderScheduler::finished);
    m_window->versionsDock()->refresh();
    QVERIFY(m_window->versionsDock()->compareInRender(3));
    QVERIFY(dock->comparisonImage().isNull());  // not the old version's image meanwhile
    waitComparison();
    QCOMPARE(rendered.count(), 1);
    QVERIFY2(dock->comparisonLabel().endsWith(QStringLiteral(", version 3")),
             qPrintable(dock->comparisonLabel()));
    QVERIFY(dock->comparisonImage() != version1);
    auto db = paintlab::db::Database::open((m_dir.path() + "/lab.db").toStdString());
    const paintlab::Recipe version3 = paintlab::db::loadRecipeVersion(db, kPearl.toStdString(), 3).recipe;
    QVERIFY(dock->comparisonImage() ==
            singleRender(version3, m_window->accuracyDock()->presetFor(false)).image);
    // The plots overlay the compared version too, under the render dock's label.
    paintlab::gui::PlotsDock* plots = m_window->plotsDock();
    QTRY_VERIFY_WITH_TIMEOUT(!plots->computing() && plots->inplanePlot()->hasComparison(), kWaitMs);
    QCOMPARE(plots->comparisonLabel(), dock->comparisonLabel());
    // Pinning the edited recipe: both sides are then the same recipe.
    m_window->renderDock()->findChild<QPushButton*>(QStringLiteral("pin_comparison"))->click();
    QVERIFY(dock->comparisonLabel().contains(QStringLiteral("pinned")));
    waitComparison();
    QVERIFY(dock->comparisonImage() == dock->image());
    m_window->clearComparison();
    QVERIFY(!dock->hasComparison());
    QVERIFY(dock->mode() == paintlab::gui::CompareMode::Single);
    QVERIFY(!plots->inplanePlot()->hasComparison() && plots->comparisonLabel().isEmpty());
}
