// The depth-profile editor (gui/src/depth_profile_*.{h,cpp}) under a virtual
// X server (gui.depth_profile in tests/gui/CMakeLists.txt, in xvfb-run like
// the other GUI tests): node drags, added and removed nodes, presets and the
// uniform reset change the recipe's depth_profile as one undo step each, the
// document announces every change (interactive while a node is held, final
// on release), undo restores the previous recipe exactly, and invalid
// profiles are refused with a message naming the field while the recipe
// keeps its valid one. No database, scene or VTK widget is needed: the
// editor works on a RecipeDocument alone.
//
// Mouse events are sent directly (QMouseEvent with explicit buttons) so a
// drag carries the held button on every move, whatever QTest's mouse state.

#include "depth_profile_edit.h"
#include "depth_profile_editor.h"
#include "depth_profile_plot.h"
#include "depth_profile_section.h"
#include "recipe_document.h"
#include "recipe_editor_dock.h"
#include "replace_recipe_command.h"
#include "save_screenshot.h"
#include "test_recipes.h"

#include "paintlab/engine/recipe_validation.h"

#include <QApplication>
#include <QDir>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <variant>

using paintlab::DepthProfile;
using paintlab::Recipe;
using paintlab::gui::DepthProfileEditor;
using paintlab::gui::DepthProfilePlot;
using paintlab::gui::DepthProfilePreset;
using paintlab::gui::RecipeDocument;

namespace {

// The basecoat (layer index 1, 10 µm) holds the pearl flakes (component 0,
// 4 %, technological limit 30 %), a pigment (component 1, 5 %) and mirror
// flakes (component 2, 2 %).
constexpr int kLayer = 1;
constexpr int kPearl = 0;

Recipe pearlescent() {
    Recipe recipe = paintlab::test::smallPearlescent(paintlab::test::pigment(0.05, 0.5, 5.0, 0.3), 0.3);
    recipe.layers[kLayer].components.push_back(paintlab::test::mirrorFlake(0.02, 10.0, 0.8));  // component 2
    return recipe;
}

const std::optional<DepthProfile>& pearlProfile(const RecipeDocument& document) {
    return *paintlab::gui::componentProfile(document.recipe(), kLayer, kPearl);
}

bool hasErrors(const Recipe& recipe) {
    for (const auto& problem : paintlab::checkRecipe(recipe))
        if (problem.severity == paintlab::Severity::Error) return true;
    return false;
}

void sendMouse(QWidget* widget, QEvent::Type type, QPointF at, Qt::MouseButton button,
               Qt::MouseButtons held) {
    QMouseEvent event(type, at, widget->mapToGlobal(at), button, held, Qt::NoModifier);
    QApplication::sendEvent(widget, &event);
}

// Press at `from`, move in `steps` equal steps to `to` holding the left button, release there.
void drag(QWidget* widget, QPointF from, QPointF to, int steps) {
    sendMouse(widget, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    for (int i = 1; i <= steps; ++i)
        sendMouse(widget, QEvent::MouseMove, from + (to - from) * (double(i) / steps), Qt::NoButton,
                  Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
}

void doubleClick(QWidget* widget, QPointF at) {
    sendMouse(widget, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
    sendMouse(widget, QEvent::MouseButtonDblClick, at, Qt::LeftButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
}

void rightClick(QWidget* widget, QPointF at) {
    sendMouse(widget, QEvent::MouseButtonPress, at, Qt::RightButton, Qt::RightButton);
    sendMouse(widget, QEvent::MouseButtonRelease, at, Qt::RightButton, Qt::NoButton);
}

using paintlab::test::saveScreenshot;

}  // namespace

class DepthProfileTest : public QObject {
    Q_OBJECT

private slots:
    void init();
    void cleanup();
    void presetsHaveTheirClosedForms();
    void dragChangesTheProfileAsOneUndoStep();
    void dragOfAnInnerNodeStaysBetweenItsNeighbours();
    void dragBackToTheStartLeavesNoUndoStep();
    void nodesAreAddedAndRemovedButNotTheEnds();
    void invalidProfilesAreRefusedWithTheField();
    void typedNodeValuesAreCheckedToo();
    void anInvalidRecipeTakesOnlyAMendingProfile();
    void uniformResetRemovesTheProfile();
    void recipeEditorOpensTheEditorPerComponent();
    void onlyPigmentsAndFlakesHaveAProfile();

private:
    DepthProfilePlot* plot() const { return m_editor->plot(); }
    std::unique_ptr<RecipeDocument> m_document;
    std::unique_ptr<DepthProfileEditor> m_editor;
};

void DepthProfileTest::init() {
    m_document = std::make_unique<RecipeDocument>();
    m_document->load(pearlescent(), "test", 0);
    QVERIFY(!hasErrors(m_document->recipe()));
    m_editor = std::make_unique<DepthProfileEditor>(m_document.get(), kLayer, kPearl);
    m_editor->resize(520, 420);
    m_editor->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_editor.get()));
}

void DepthProfileTest::cleanup() {
    m_editor.reset();
    m_document.reset();
}

void DepthProfileTest::presetsHaveTheirClosedForms() {
    // Piecewise-linear weights integrate exactly with the trapezoid rule:
    // enriched top = 3 * 0.2 + (3 + 1) / 2 * 0.1 + 1 * 0.7 = 1.5, peak 3 / 1.5 = 2
    // (settled is its mirror image); gradient (0.5 + 1.5) / 2 = 1, peak 1.5.
    struct Expected {
        DepthProfilePreset preset;
        double mean;
        double peak;
    };
    for (const Expected& e : {Expected{DepthProfilePreset::Uniform, 1.0, 1.0},
                              Expected{DepthProfilePreset::EnrichedTop, 1.5, 2.0},
                              Expected{DepthProfilePreset::Settled, 1.5, 2.0},
                              Expected{DepthProfilePreset::LinearGradient, 1.0, 1.5}}) {
        const DepthProfile profile = paintlab::gui::presetProfile(e.preset);
        QVERIFY(paintlab::gui::depthProfileProblem(profile).empty());
        QCOMPARE_LE(std::abs(profile.meanWeight() - e.mean), 1e-12);
        QCOMPARE_LE(std::abs(profile.peakRelativeConcentration() - e.peak), 1e-12);
    }
    // Enriched at the top really is richer near the top, settled near the bottom.
    const DepthProfile top = paintlab::gui::presetProfile(DepthProfilePreset::EnrichedTop);
    const DepthProfile settled = paintlab::gui::presetProfile(DepthProfilePreset::Settled);
    QCOMPARE(top.weightAt(0.1), 3.0);
    QCOMPARE(top.weightAt(0.9), 1.0);
    QCOMPARE(settled.weightAt(0.1), 1.0);
    QCOMPARE(settled.weightAt(0.9), 3.0);

    // Through the editor: each preset is one undo step, the recipe stays valid
    // and the shown statistics are the profile's.
    QUndoStack* undo = m_document->undoStack();
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::Settled));
    QCOMPARE(undo->count(), 1);
    QVERIFY(pearlProfile(*m_document).has_value());
    QCOMPARE(*pearlProfile(*m_document), settled);
    QVERIFY(!hasErrors(m_document->recipe()));
    QVERIFY2(m_editor->statistics().contains("mean weight 1.5"), qPrintable(m_editor->statistics()));
    QVERIFY2(m_editor->statistics().contains("peak relative concentration 2 "),
             qPrintable(m_editor->statistics()));
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::LinearGradient));
    QCOMPARE(undo->count(), 2);
    QVERIFY2(m_editor->statistics().contains("peak relative concentration 1.5 "),
             qPrintable(m_editor->statistics()));
    // The uniform preset is no profile at all.
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::Uniform));
    QVERIFY(!pearlProfile(*m_document).has_value());
    QCOMPARE(undo->count(), 3);
}

void DepthProfileTest::dragChangesTheProfileAsOneUndoStep() {
    const Recipe before = m_document->recipe();
    QVERIFY(!pearlProfile(*m_document).has_value());
    QVERIFY2(plot()->depthAxisTitle().contains("10 µm"), qPrintable(plot()->depthAxisTitle()));
    QSignalSpy changed(m_document.get(), &RecipeDocument::recipeChanged);

    // The top end node, dragged up (and sideways: an end node keeps its depth).
    const QPointF from = plot()->nodePosition(0);
    const QPointF to = from + QPointF(25.0, -40.0);
    const double expected_weight = plot()->valueAt(to).y();
    QVERIFY(expected_weight > 1.2);
    drag(plot(), from, to, 8);

    QVERIFY(pearlProfile(*m_document).has_value());
    const DepthProfile after = *pearlProfile(*m_document);
    QCOMPARE(after.depth, (std::vector<double>{0.0, 1.0}));
    QCOMPARE_LE(std::abs(after.weight[0] - expected_weight), 1e-9);
    QCOMPARE(after.weight[1], 1.0);
    QVERIFY(!hasErrors(m_document->recipe()));
    // Every move announced while held, then one final edit on release.
    QCOMPARE(changed.count(), 9);
    for (int i = 0; i < 8; ++i) QCOMPARE(changed.at(i).at(0).toBool(), true);
    QCOMPARE(changed.at(8).at(0).toBool(), false);
    // One undo step for the whole drag.
    QUndoStack* undo = m_document->undoStack();
    QCOMPARE(undo->count(), 1);
    undo->undo();
    QVERIFY(m_document->recipe() == before);
    QVERIFY(!pearlProfile(*m_document).has_value());
    QCOMPARE(plot()->profile(), paintlab::gui::presetProfile(DepthProfilePreset::Uniform));
    undo->redo();
    QCOMPARE(*pearlProfile(*m_document), after);

    // A second drag is a second step; undoing it restores the first drag's profile exactly.
    const Recipe after_first = m_document->recipe();
    drag(plot(), plot()->nodePosition(1), plot()->nodePosition(1) + QPointF(0.0, -30.0), 5);
    QCOMPARE(undo->count(), 2);
    QVERIFY(pearlProfile(*m_document)->weight[1] > 1.0);
    undo->undo();
    QVERIFY(m_document->recipe() == after_first);
    saveScreenshot(m_editor.get(), "depth_profile_editor");
}

void DepthProfileTest::dragOfAnInnerNodeStaysBetweenItsNeighbours() {
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::EnrichedTop));  // nodes at 0, 0.2, 0.3, 1
    const Recipe before = m_document->recipe();
    // Node 2 (depth 0.2) dragged far past node 3 (0.3) and below the axis.
    const QPointF from = plot()->nodePosition(1);
    drag(plot(), from, from + QPointF(400.0, 400.0), 10);
    const DepthProfile after = *pearlProfile(*m_document);
    QCOMPARE(after.depth.size(), std::size_t{4});
    QCOMPARE_LE(std::abs(after.depth[1] - (0.3 - paintlab::gui::kMinNodeSpacing)), 1e-12);
    QCOMPARE(after.weight[1], 0.0);
    QVERIFY(paintlab::gui::depthProfileProblem(after).empty());
    QCOMPARE(m_document->undoStack()->count(), 2);  // the preset, the drag
    m_document->undoStack()->undo();
    QVERIFY(m_document->recipe() == before);
}

void DepthProfileTest::dragBackToTheStartLeavesNoUndoStep() {
    QVERIFY(m_editor->apply(DepthProfile{{0.0, 1.0}, {0.0, 1.0}}));
    const Recipe before = m_document->recipe();
    QSignalSpy changed(m_document.get(), &RecipeDocument::recipeChanged);
    // The top node (weight 0) up, then down past the axis: the weight is clipped back to 0 exactly.
    const QPointF from = plot()->nodePosition(0);
    sendMouse(plot(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    for (const double dy : {-20.0, -40.0, -20.0, 30.0})
        sendMouse(plot(), QEvent::MouseMove, from + QPointF(0.0, dy), Qt::NoButton, Qt::LeftButton);
    sendMouse(plot(), QEvent::MouseButtonRelease, from + QPointF(0.0, 30.0), Qt::LeftButton, Qt::NoButton);
    QVERIFY(m_document->recipe() == before);
    QCOMPARE(m_document->undoStack()->count(), 1);  // only the first apply
    QCOMPARE(m_document->undoStack()->index(), 1);
    QVERIFY(changed.count() >= 2);
    QCOMPARE(changed.last().at(0).toBool(), false);  // the release still announces the final state
}

void DepthProfileTest::nodesAreAddedAndRemovedButNotTheEnds() {
    QUndoStack* undo = m_document->undoStack();
    // Double-click in the middle of the layer, at weight ~2.
    const QPointF top = plot()->nodePosition(0);
    const QPointF bottom = plot()->nodePosition(1);
    QPointF at((top.x() + bottom.x()) / 2.0, top.y() - 40.0);
    const QPointF value = plot()->valueAt(at);
    doubleClick(plot(), at);
    QVERIFY(pearlProfile(*m_document).has_value());
    DepthProfile added = *pearlProfile(*m_document);
    QCOMPARE(added.depth.size(), std::size_t{3});
    QCOMPARE_LE(std::abs(added.depth[1] - value.x()), 1e-12);
    QCOMPARE_LE(std::abs(added.weight[1] - value.y()), 1e-12);
    QCOMPARE(plot()->selectedNode(), 1);
    QCOMPARE(undo->count(), 1);

    // Right-click on an end node: refused, named, nothing changes.
    rightClick(plot(), plot()->nodePosition(2));
    QVERIFY2(m_editor->message().contains("depth_profile.depth[2]"), qPrintable(m_editor->message()));
    QCOMPARE(pearlProfile(*m_document)->depth.size(), std::size_t{3});
    QCOMPARE(undo->count(), 1);

    // Right-click on the new node removes it.
    rightClick(plot(), plot()->nodePosition(1));
    QCOMPARE(pearlProfile(*m_document)->depth.size(), std::size_t{2});
    QCOMPARE(undo->count(), 2);
    QVERIFY(m_editor->message().isEmpty());

    // Select a node (a press without a move is no edit) and press Delete.
    undo->undo();
    QCOMPARE(*pearlProfile(*m_document), added);
    sendMouse(plot(), QEvent::MouseButtonPress, plot()->nodePosition(1), Qt::LeftButton, Qt::LeftButton);
    sendMouse(plot(), QEvent::MouseButtonRelease, plot()->nodePosition(1), Qt::LeftButton, Qt::NoButton);
    QCOMPARE(plot()->selectedNode(), 1);
    QCOMPARE(undo->count(), 2);  // the removal is still there to redo: nothing pushed by the click
    QCOMPARE(undo->index(), 1);
    QTest::keyClick(plot(), Qt::Key_Delete);
    QCOMPARE(pearlProfile(*m_document)->depth.size(), std::size_t{2});
    QCOMPARE(undo->index(), 2);
    undo->undo();
    QCOMPARE(*pearlProfile(*m_document), added);
}

void DepthProfileTest::invalidProfilesAreRefusedWithTheField() {
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::Settled));
    const Recipe valid = m_document->recipe();
    QUndoStack* undo = m_document->undoStack();
    QSignalSpy changed(m_document.get(), &RecipeDocument::recipeChanged);
    struct Case {
        DepthProfile profile;
        const char* expected;  // what the message must name
    };
    const Case cases[] = {
        {{{0.0, 0.6, 0.4, 1.0}, {1.0, 1.0, 1.0, 1.0}}, "depth_profile.depth[2]"},
        {{{0.0, 0.5, 0.5, 1.0}, {1.0, 1.0, 1.0, 1.0}}, "depth_profile.depth[2]"},
        {{{0.0, 0.9}, {1.0, 1.0}}, "depth_profile.depth[1]"},
        {{{0.1, 1.0}, {1.0, 1.0}}, "depth_profile.depth[0]"},
        {{{0.0, 0.5, 1.0}, {1.0, -0.5, 1.0}}, "depth_profile.weight[1]"},
        {{{0.0, 0.5, 1.0}, {0.0, 0.0, 0.0}}, "all weights are zero"},
        {{{0.0, 0.5, 1.0}, {1.0, 1.0}}, "every node needs both"},
        {{{0.0, 1.0}, {1.0, std::nan("")}}, "depth_profile.weight[1]"},
        {{{0.0, 1.0}, {1.0, 2000.0}}, "depth_profile.weight[1]: 2000 is above the maximum 1000"},
        {{{0.0}, {1.0}}, "needs at least two nodes"},
        // Valid in shape, but 4 % flakes x peak 200 = 80 % > their 30 % limit: the engine's check.
        {{{0.0, 0.01, 1.0}, {100.0, 0.0, 0.0}}, "depth_profile: the profile's peak volume fraction"},
    };
    for (const Case& c : cases) {
        QVERIFY(!m_editor->apply(c.profile));
        QVERIFY2(m_editor->message().contains(c.expected), qPrintable(m_editor->message()));
        QVERIFY(m_document->recipe() == valid);
        QCOMPARE(undo->count(), 1);
        QCOMPARE(plot()->profile(), *pearlProfile(*m_document));  // the chart shows the recipe's
    }
    QCOMPARE(changed.count(), 0);

    // A drag that would leave every weight at zero: refused while dragging, the
    // recipe keeps the last valid state.
    QVERIFY(m_editor->apply(DepthProfile{{0.0, 1.0}, {0.0, 1.0}}));
    QVERIFY(m_editor->message().isEmpty());
    const QPointF node = plot()->nodePosition(1);
    drag(plot(), node, node + QPointF(0.0, 500.0), 4);
    QVERIFY2(m_editor->message().contains("all weights are zero"), qPrintable(m_editor->message()));
    QVERIFY(pearlProfile(*m_document)->weight[1] > 0.0);
    QVERIFY(!hasErrors(m_document->recipe()));
}

void DepthProfileTest::typedNodeValuesAreCheckedToo() {
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::EnrichedTop));  // nodes at 0, 0.2, 0.3, 1
    const Recipe valid = m_document->recipe();
    plot()->selectNode(1);
    auto* depth = m_editor->findChild<QLineEdit*>("depth_profile_node_depth");
    auto* weight = m_editor->findChild<QLineEdit*>("depth_profile_node_weight");
    QVERIFY(depth != nullptr && weight != nullptr);
    QCOMPARE(depth->text(), QString("0.2"));
    QCOMPARE(weight->text(), QString("3"));

    auto type = [](QLineEdit* field, const QString& text) {
        field->setText(text);
        emit field->editingFinished();
    };
    type(depth, "0.45");  // past node 3 at 0.3
    QVERIFY2(m_editor->message().contains("depth_profile.depth[2]"), qPrintable(m_editor->message()));
    QVERIFY(m_document->recipe() == valid);
    QCOMPARE(depth->text(), QString("0.2"));  // the field shows the recipe's value again
    type(weight, "-1");
    QVERIFY2(m_editor->message().contains("depth_profile.weight[1]"), qPrintable(m_editor->message()));
    QVERIFY(m_document->recipe() == valid);
    type(weight, "lots");
    QVERIFY2(m_editor->message().contains("'lots' is not a number"), qPrintable(m_editor->message()));
    QVERIFY(m_document->recipe() == valid);
    QCOMPARE(m_document->undoStack()->count(), 1);

    type(depth, "0.25");
    QVERIFY(m_editor->message().isEmpty());
    QCOMPARE(pearlProfile(*m_document)->depth[1], 0.25);
    QCOMPARE(m_document->undoStack()->count(), 2);
    QVERIFY(depth->isReadOnly() == false);
    plot()->selectNode(0);
    QVERIFY(depth->isReadOnly());  // the end nodes stay at 0 and 1
}

// A concentration slider can leave the recipe invalid (18 % pearl x settled
// peak 2 = 36 % > 30 %): a profile edit that keeps it invalid is refused
// even with the same peak, one that mends it is taken.
void DepthProfileTest::anInvalidRecipeTakesOnlyAMendingProfile() {
    Recipe invalid = pearlescent();
    auto& pearl = std::get<paintlab::InterferenceFlake>(invalid.layers[kLayer].components[kPearl]);
    pearl.volume_fraction = 0.18;
    pearl.depth_profile = paintlab::gui::presetProfile(DepthProfilePreset::Settled);
    m_document->load(invalid, "test", 0);
    QVERIFY(hasErrors(m_document->recipe()));
    QCOMPARE(plot()->profile(), paintlab::gui::presetProfile(DepthProfilePreset::Settled));
    QVERIFY(!m_editor->applyPreset(DepthProfilePreset::EnrichedTop));  // peak 2 as well
    QVERIFY2(m_editor->message().contains("depth_profile: the profile's peak volume fraction 0.36"),
             qPrintable(m_editor->message()));
    QVERIFY(m_document->recipe() == invalid);
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::LinearGradient));  // peak 1.5: 27 %
    QVERIFY(!hasErrors(m_document->recipe()));
    QCOMPARE(m_document->undoStack()->count(), 1);
}

void DepthProfileTest::uniformResetRemovesTheProfile() {
    auto* uniform = m_editor->findChild<QPushButton*>("depth_profile_uniform");
    QVERIFY(uniform != nullptr);
    QVERIFY(!uniform->isEnabled());  // nothing to remove yet
    QVERIFY(m_editor->applyPreset(DepthProfilePreset::EnrichedTop));
    const Recipe shaped = m_document->recipe();
    QVERIFY(uniform->isEnabled());
    QTest::mouseClick(uniform, Qt::LeftButton);
    QVERIFY(!pearlProfile(*m_document).has_value());
    QVERIFY2(m_editor->statistics().contains("uniform"), qPrintable(m_editor->statistics()));
    QCOMPARE(m_document->undoStack()->count(), 2);
    m_document->undoStack()->undo();
    QVERIFY(m_document->recipe() == shaped);
}

void DepthProfileTest::recipeEditorOpensTheEditorPerComponent() {
    m_editor.reset();
    paintlab::gui::RecipeEditorDock dock(m_document.get());
    m_document->load(pearlescent(), "test", 0);  // the dock builds its rows on a load
    dock.resize(520, 900);
    dock.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dock));
    // The parameter rows are still there, and one section per pigment or flake
    // (the basecoat's pearl, pigment and mirror flakes; the clear coat has no components).
    QVERIFY(dock.sliderFor("volume_fraction") != nullptr);
    const auto sections = dock.findChildren<paintlab::gui::DepthProfileSection*>();
    QCOMPARE(sections.size(), qsizetype{3});
    auto* section = dock.findChild<paintlab::gui::DepthProfileSection*>("depth_profile_section_1_0");
    QVERIFY(section != nullptr);
    QVERIFY(section->editor() == nullptr);
    QTest::mouseClick(section->button(), Qt::LeftButton);
    QVERIFY(section->editor() != nullptr);
    QVERIFY(section->editor()->isVisible());
    QVERIFY(section->editor()->applyPreset(DepthProfilePreset::Settled));
    QCOMPARE(*pearlProfile(*m_document), paintlab::gui::presetProfile(DepthProfilePreset::Settled));
    // A profile edit does not rebuild the dock: the open editor stays.
    QVERIFY(section->editor()->isVisible());
    // Laid out (posted layout requests) with the chart at its full height, above its controls.
    QTest::qWait(50);
    DepthProfilePlot* chart = section->editor()->plot();
    QCOMPARE_GE(chart->height(), 200);
    auto* presets = section->editor()->findChild<QWidget*>("depth_profile_presets");
    QVERIFY(presets != nullptr);
    QCOMPARE_GE(presets->mapTo(section->editor(), QPoint(0, 0)).y(),
                chart->mapTo(section->editor(), QPoint(0, chart->height())).y());
    saveScreenshot(&dock, "depth_profile_dock");
    // A component added to the layer rebuilds the rows; the open editor is open again.
    Recipe added = m_document->recipe();
    paintlab::Pigment second = paintlab::test::pigment(0.01, 0.1, 1.0, 0.0);
    second.name = "second pigment";
    added.layers[kLayer].components.push_back(second);
    m_document->undoStack()->push(new paintlab::gui::ReplaceRecipeCommand(m_document.get(), added, "add"));
    QCOMPARE(dock.findChildren<paintlab::gui::DepthProfileSection*>().size(), qsizetype{4});
    section = dock.findChild<paintlab::gui::DepthProfileSection*>("depth_profile_section_1_0");
    QVERIFY(section != nullptr && section->isOpen() && section->editor() != nullptr);
    QVERIFY(!dock.findChild<paintlab::gui::DepthProfileSection*>("depth_profile_section_1_1")->isOpen());
    QCOMPARE(section->editor()->plot()->profile(), paintlab::gui::presetProfile(DepthProfilePreset::Settled));
    QTest::mouseClick(section->button(), Qt::LeftButton);
    QVERIFY(!section->editor()->isVisible());
}

void DepthProfileTest::onlyPigmentsAndFlakesHaveAProfile() {
    Recipe recipe = m_document->recipe();
    for (int c = 0; c < 3; ++c) QVERIFY(paintlab::gui::componentProfile(recipe, kLayer, c) != nullptr);
    recipe.layers[kLayer].components.push_back(paintlab::test::rawMedium(0.5, 1.0, 0.0));
    QVERIFY(paintlab::gui::componentProfile(recipe, kLayer, 3) == nullptr);
    QVERIFY(paintlab::gui::componentProfile(recipe, kLayer, 4) == nullptr);
    QVERIFY(paintlab::gui::componentProfile(recipe, 0, 0) == nullptr);  // the clear coat has none
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, paintlab::gui::withProfile(recipe, kLayer, 3, std::nullopt));
    // The mirror flakes' editor works like the pearl's.
    DepthProfileEditor mirror(m_document.get(), kLayer, 2);
    QVERIFY(mirror.applyPreset(DepthProfilePreset::EnrichedTop));
    QCOMPARE(*paintlab::gui::componentProfile(m_document->recipe(), kLayer, 2),
             paintlab::gui::presetProfile(DepthProfilePreset::EnrichedTop));
    QVERIFY(!pearlProfile(*m_document).has_value());
}

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    DepthProfileTest test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_depth_profile.moc"
