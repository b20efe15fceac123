// The recipe editor's layer list and component table (gui/src/recipe_structure*.{h,cpp})
// under a virtual X server (gui.recipe_structure in tests/gui/CMakeLists.txt,
// in xvfb-run like the other GUI tests): adding, removing, moving and
// renaming layers and removing and moving components change the recipe as
// expected, each as one undo step whose undo restores the previous recipe
// exactly; refused edits (the only layer removed, an empty or taken name)
// name the field and leave the recipe and the undo stack alone; the
// parameter rows rebuild; the Ingredients dock adds to the layer selected
// here; and a structure edit reaches the render scheduler (the document's
// recipeChanged, as the main window wires it) and renders.
// No database, scene or VTK widget is needed.

#include "depth_profile_section.h"
#include "ingredient_dock.h"
#include "recipe_document.h"
#include "recipe_editor_dock.h"
#include "recipe_structure.h"
#include "recipe_structure_panel.h"
#include "render_scheduler.h"
#include "test_recipes.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/parameters.h"
#include "paintlab/engine/recipe_validation.h"

#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGroupBox>
#include <QLineEdit>
#include <QListWidget>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include <memory>
#include <variant>

using paintlab::Recipe;
using paintlab::gui::RecipeDocument;
using paintlab::gui::RecipeEditorDock;
using paintlab::gui::RecipeStructurePanel;

namespace {

// Layer 0 "layer" (20 µm, n 1.55, no components) over layer 1 "basecoat"
// (10 µm): the pearl (interference flake, 4 %), the pigment (5 %) and the
// mirror flakes (2 %).
constexpr int kBase = 1;

Recipe pearlescent() {
    Recipe recipe = paintlab::test::smallPearlescent(paintlab::test::pigment(0.05, 0.5, 5.0, 0.3), 0.3);
    recipe.layers[kBase].components.emplace_back(paintlab::test::mirrorFlake(0.02, 10.0, 0.8));
    return recipe;
}

std::vector<std::string> layerNames(const Recipe& recipe) {
    std::vector<std::string> names;
    for (const auto& layer : recipe.layers) names.push_back(layer.name);
    return names;
}

std::vector<std::string> componentNames(const Recipe& recipe, int layer) {
    std::vector<std::string> names;
    for (const auto& c : recipe.layers[static_cast<std::size_t>(layer)].components)
        names.push_back(paintlab::componentName(c));
    return names;
}

bool hasErrors(const Recipe& recipe) {
    for (const auto& problem : paintlab::checkRecipe(recipe))
        if (problem.severity == paintlab::Severity::Error) return true;
    return false;
}

}  // namespace

class RecipeStructureTest : public QObject {
    Q_OBJECT

private slots:
    void init();
    void cleanup();
    void editsChangeTheRecipeAsExpected();
    void addedLayerIsAClearLacquerAboveTheSelection();
    void removedLayerIsOneUndoStep();
    void theOnlyLayerCannotBeRemoved();
    void layersMoveUpAndDownWithTheSelection();
    void renameByEditingTheListItem();
    void emptyOrTakenNamesAreRefused();
    void componentsAreRemovedAndMoved();
    void anErrorTheRecipeAlreadyHadDoesNotBlockAMove();
    void openDepthProfileEditorsFollowTheirComponent();
    void theIngredientsDockAddsToTheSelectedLayer();
    void aStructureEditReachesTheRenderScheduler();

private:
    RecipeStructurePanel* panel() const { return m_dock->structurePanel(); }
    QToolButton* button(const char* name) const {
        auto* b = m_dock->findChild<QToolButton*>(QString::fromLatin1(name));
        if (b == nullptr) qFatal("no button %s", name);
        return b;
    }
    // Undo, redo and undo again of the last step: before / after exactly.
    void checkUndoRedo(const Recipe& before, const Recipe& after) const;
    QStringList groupTitles() const;

    std::unique_ptr<RecipeDocument> m_document;
    std::unique_ptr<RecipeEditorDock> m_dock;
};

void RecipeStructureTest::init() {
    m_document = std::make_unique<RecipeDocument>();
    m_dock = std::make_unique<RecipeEditorDock>(m_document.get());
    m_document->load(pearlescent(), "test", 0);
    QVERIFY(!hasErrors(m_document->recipe()));
    m_dock->resize(420, 700);
    m_dock->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_dock.get()));
    QCOMPARE(panel()->layerList()->count(), 2);
    QCOMPARE(panel()->selectedLayer(), 0);
}

void RecipeStructureTest::cleanup() {
    m_dock.reset();
    m_document.reset();
}

void RecipeStructureTest::checkUndoRedo(const Recipe& before, const Recipe& after) const {
    QUndoStack* undo = m_document->undoStack();
    QVERIFY(m_document->recipe() == after);
    undo->undo();
    QVERIFY(m_document->recipe() == before);
    undo->redo();
    QVERIFY(m_document->recipe() == after);
    undo->undo();
    QVERIFY(m_document->recipe() == before);
}

QStringList RecipeStructureTest::groupTitles() const {
    QStringList titles;
    for (const auto* box : m_dock->findChildren<QGroupBox*>())
        if (!panel()->isAncestorOf(box)) titles << box->title();
    return titles;
}

void RecipeStructureTest::editsChangeTheRecipeAsExpected() {
    using namespace paintlab::gui;
    const Recipe r = pearlescent();
    // The declared default thickness (0) is not allowed: the middle of the typical 1-100 µm.
    QCOMPARE(newLayerThicknessUm(), 50.5);
    QVERIFY(paintlab::params::kLayerThickness.allows(newLayerThicknessUm()));

    StructureEdit added = withLayerAdded(r, 2);
    QCOMPARE(added.recipe.layers.size(), std::size_t{3});
    QCOMPARE(added.recipe.layers[2].name, std::string("clear coat"));
    QCOMPARE(added.recipe.layers[2].binder, r.layers[0].binder);
    QVERIFY(added.recipe.layers[2].components.empty());
    QCOMPARE(added.text, std::string("Add layer 'clear coat'"));
    // The name is taken now: the next one is numbered.
    QCOMPARE(withLayerAdded(added.recipe, 0).recipe.layers[0].name, std::string("clear coat 2"));

    StructureEdit moved = withLayerMoved(r, 0, 1);
    QCOMPARE(layerNames(moved.recipe), (std::vector<std::string>{"basecoat", "layer"}));
    QCOMPARE(moved.recipe.layers[0], r.layers[1]);
    QCOMPARE(moved.text, std::string("Move layer 'layer' down"));

    StructureEdit three = withLayerAdded(r, 0);  // clear coat, layer, basecoat
    QCOMPARE(layerNames(withLayerMoved(three.recipe, 2, 0).recipe),
             (std::vector<std::string>{"basecoat", "clear coat", "layer"}));
    QCOMPARE(layerNames(withLayerMoved(three.recipe, 0, 2).recipe),
             (std::vector<std::string>{"layer", "basecoat", "clear coat"}));

    StructureEdit removed = withComponentRemoved(r, kBase, 1);
    QCOMPARE(componentNames(removed.recipe, kBase), (std::vector<std::string>{"pearl", "mirror"}));
    QCOMPARE(removed.text, std::string("Remove pigment 'pigment' from 'basecoat'"));
    StructureEdit down = withComponentMoved(r, kBase, 0, 2);
    QCOMPARE(componentNames(down.recipe, kBase), (std::vector<std::string>{"pigment", "mirror", "pearl"}));
    QCOMPARE(down.text, std::string("Move interference flake 'pearl' down in 'basecoat'"));

    QCOMPARE(withLayerRenamed(r, 1, "  base  ").recipe.layers[1].name, std::string("base"));

    // Out of range: InputError naming the field.
    try {
        (void)withComponentRemoved(r, kBase, 3);
        QFAIL("a fourth component was removed");
    } catch (const paintlab::InputError& e) {
        QCOMPARE(e.field(), std::string("layers[1].components[3]"));
    }
    QVERIFY_THROWS_EXCEPTION(paintlab::InputError, withLayerMoved(r, 0, -1));
    QVERIFY_THROWS_EXCEPTION(paintlab::InputError, withLayerRemoved(r, 2));
    QVERIFY_THROWS_EXCEPTION(paintlab::InputError, withComponentMoved(r, 0, 0, 1));  // layer 0 is empty
}

void RecipeStructureTest::addedLayerIsAClearLacquerAboveTheSelection() {
    const Recipe before = m_document->recipe();
    const auto rows_before = m_dock->findChildren<QDoubleSpinBox*>().size();
    panel()->selectLayer(kBase);
    QSignalSpy changed(m_document.get(), &RecipeDocument::recipeChanged);
    button("structure_add_layer")->click();
    QCOMPARE(changed.count(), 1);
    const Recipe& after = m_document->recipe();
    QCOMPARE(layerNames(after), (std::vector<std::string>{"layer", "clear coat", "basecoat"}));
    QCOMPARE(after.layers[1].thickness_um, 50.5);
    QCOMPARE(after.layers[1].binder, before.layers[0].binder);
    QVERIFY(after.layers[1].components.empty());
    QVERIFY(!hasErrors(after));
    QCOMPARE(m_document->undoStack()->count(), 1);
    QCOMPARE(m_document->undoStack()->undoText(), QStringLiteral("Add layer 'clear coat'"));
    // The list shows it, selected; the rows have the new layer's thickness.
    QCOMPARE(panel()->layerList()->count(), 3);
    QCOMPARE(panel()->layerList()->item(1)->text(), QStringLiteral("clear coat"));
    QCOMPARE(panel()->selectedLayer(), 1);
    QVERIFY(groupTitles().contains(QStringLiteral("clear coat")));
    QCOMPARE(m_dock->findChildren<QDoubleSpinBox*>().size(), rows_before + 1);  // its thickness
    QVERIFY(panel()->message().isEmpty());
    checkUndoRedo(before, Recipe(after));
    QCOMPARE(panel()->layerList()->count(), 2);
    QCOMPARE(m_dock->findChildren<QDoubleSpinBox*>().size(), rows_before);
}

void RecipeStructureTest::removedLayerIsOneUndoStep() {
    const Recipe before = m_document->recipe();
    const auto rows_before = m_dock->findChildren<QDoubleSpinBox*>().size();
    panel()->selectLayer(kBase);
    QVERIFY(button("structure_remove_layer")->isEnabled());
    button("structure_remove_layer")->click();
    QCOMPARE(layerNames(m_document->recipe()), (std::vector<std::string>{"layer"}));
    QCOMPARE(m_document->recipe().layers[0], before.layers[0]);
    QCOMPARE(m_document->undoStack()->count(), 1);
    QCOMPARE(m_document->undoStack()->undoText(), QStringLiteral("Remove layer 'basecoat'"));
    QCOMPARE(panel()->selectedLayer(), 0);
    // Only the remaining layer's thickness row is left.
    QCOMPARE(m_dock->findChildren<QDoubleSpinBox*>().size(), 1);
    checkUndoRedo(before, Recipe(m_document->recipe()));
    QCOMPARE(m_dock->findChildren<QDoubleSpinBox*>().size(), rows_before);
}

void RecipeStructureTest::theOnlyLayerCannotBeRemoved() {
    panel()->selectLayer(kBase);
    QVERIFY(panel()->removeLayer());
    const Recipe one_layer = m_document->recipe();
    QCOMPARE(one_layer.layers.size(), std::size_t{1});
    QVERIFY(!button("structure_remove_layer")->isEnabled());
    QSignalSpy changed(m_document.get(), &RecipeDocument::recipeChanged);
    QVERIFY(!panel()->removeLayer());  // past the disabled button: the validation refuses
    QVERIFY2(panel()->message().contains("layers: the recipe has no layers"), qPrintable(panel()->message()));
    QVERIFY(m_document->recipe() == one_layer);
    QCOMPARE(m_document->undoStack()->count(), 1);
    QCOMPARE(changed.count(), 0);
    // The next accepted edit clears the message.
    QVERIFY(panel()->addLayer());
    QVERIFY(panel()->message().isEmpty());
}

void RecipeStructureTest::layersMoveUpAndDownWithTheSelection() {
    const Recipe before = m_document->recipe();
    panel()->selectLayer(kBase);
    QVERIFY(!button("structure_layer_down")->isEnabled());
    QVERIFY(button("structure_layer_up")->isEnabled());
    button("structure_layer_up")->click();
    QCOMPARE(layerNames(m_document->recipe()), (std::vector<std::string>{"basecoat", "layer"}));
    QCOMPARE(m_document->recipe().layers[0], before.layers[1]);
    QCOMPARE(m_document->undoStack()->undoText(), QStringLiteral("Move layer 'basecoat' up"));
    QCOMPARE(panel()->selectedLayer(), 0);  // the selection follows the layer
    QCOMPARE(panel()->layerList()->currentItem()->text(), QStringLiteral("basecoat"));
    // The rows follow the order: the basecoat's groups come first now.
    QVERIFY2(groupTitles().front() == QStringLiteral("basecoat"), qPrintable(groupTitles().join(" | ")));
    const Recipe moved = m_document->recipe();
    button("structure_layer_down")->click();
    QVERIFY(m_document->recipe() == before);
    QCOMPARE(m_document->undoStack()->count(), 2);
    // Past the bottom: refused, named.
    QVERIFY(!panel()->moveLayer(+1));
    QVERIFY2(panel()->message().contains("layers[1]: it is already the bottom layer"),
             qPrintable(panel()->message()));
    QCOMPARE(m_document->undoStack()->count(), 2);
    m_document->undoStack()->undo();
    QVERIFY(m_document->recipe() == moved);
    m_document->undoStack()->undo();
    QVERIFY(m_document->recipe() == before);
}

void RecipeStructureTest::renameByEditingTheListItem() {
    const Recipe before = m_document->recipe();
    QListWidget* list = panel()->layerList();
    QListWidgetItem* item = list->item(kBase);
    QVERIFY(item->flags() & Qt::ItemIsEditable);
    // As a technician does: the Rename button opens the item's editor, type, Enter.
    panel()->selectLayer(kBase);
    button("structure_rename_layer")->click();
    auto* editor = list->viewport()->findChild<QLineEdit*>();
    QVERIFY(editor != nullptr);
    editor->selectAll();
    QTest::keyClicks(editor, QStringLiteral("blue basecoat"));
    QTest::keyClick(editor, Qt::Key_Return);
    QTRY_COMPARE(m_document->recipe().layers[kBase].name, std::string("blue basecoat"));
    QCOMPARE(m_document->undoStack()->count(), 1);
    QCOMPARE(m_document->undoStack()->undoText(),
             QStringLiteral("Rename layer 'basecoat' to 'blue basecoat'"));
    QCOMPARE(panel()->selectedLayer(), kBase);
    // The rows' titles follow (the parameters themselves did not change).
    QVERIFY2(groupTitles().contains(QStringLiteral("blue basecoat")), qPrintable(groupTitles().join(" | ")));
    QVERIFY(!groupTitles().contains(QStringLiteral("basecoat")));
    Recipe expected = before;
    expected.layers[kBase].name = "blue basecoat";
    checkUndoRedo(before, expected);
    QCOMPARE(panel()->layerList()->item(kBase)->text(), QStringLiteral("basecoat"));
    // The same name again is no step.
    QVERIFY(!panel()->renameLayer(QStringLiteral("basecoat")));
    QCOMPARE(m_document->undoStack()->index(), 0);
}

void RecipeStructureTest::emptyOrTakenNamesAreRefused() {
    const Recipe before = m_document->recipe();
    panel()->selectLayer(kBase);
    QVERIFY(!panel()->renameLayer(QStringLiteral("   ")));
    QVERIFY2(panel()->message().contains("layers[1].name: the layer needs a name"),
             qPrintable(panel()->message()));
    QVERIFY(m_document->recipe() == before);
    QCOMPARE(m_document->undoStack()->count(), 0);
    // Through the list: the refused text is replaced by the name again.
    panel()->layerList()->item(kBase)->setText(QStringLiteral("layer"));
    QTRY_VERIFY(panel()->message().contains("already called"));
    QVERIFY2(panel()->message().contains("layers[1].name: layer 1 is already called 'layer'"),
             qPrintable(panel()->message()));
    QVERIFY(m_document->recipe() == before);
    QCOMPARE(m_document->undoStack()->count(), 0);
    QCOMPARE(panel()->layerList()->item(kBase)->text(), QStringLiteral("basecoat"));
}

void RecipeStructureTest::componentsAreRemovedAndMoved() {
    const Recipe before = m_document->recipe();
    panel()->selectLayer(kBase);
    QTableWidget* table = panel()->componentTable();
    QCOMPARE(table->rowCount(), 3);
    QCOMPARE(table->item(0, 0)->text(), QStringLiteral("pearl"));
    QCOMPARE(table->item(0, 1)->text(), QStringLiteral("interference flake"));
    QCOMPARE(table->item(0, 2)->text(), QStringLiteral("4 %"));
    QCOMPARE(table->item(1, 2)->text(), QStringLiteral("5 %"));
    QVERIFY(!button("structure_remove_component")->isEnabled());  // nothing selected yet

    // Move the pigment up, then down again: two steps.
    panel()->selectComponent(1);
    QVERIFY(button("structure_component_up")->isEnabled());
    button("structure_component_up")->click();
    QCOMPARE(componentNames(m_document->recipe(), kBase),
             (std::vector<std::string>{"pigment", "pearl", "mirror"}));
    QCOMPARE(m_document->recipe().layers[kBase].components[0], before.layers[kBase].components[1]);
    QCOMPARE(m_document->undoStack()->undoText(), QStringLiteral("Move pigment 'pigment' up in 'basecoat'"));
    QCOMPARE(panel()->selectedComponent(), 0);
    QCOMPARE(table->item(0, 0)->text(), QStringLiteral("pigment"));
    // The rows follow: the pigment's group is the first of the basecoat.
    const QStringList titles = groupTitles();
    QVERIFY2(titles.indexOf(QRegularExpression("basecoat . pigment.*")) <
                 titles.indexOf(QRegularExpression("basecoat . pearl.*")),
             qPrintable(titles.join(" | ")));
    checkUndoRedo(before, Recipe(m_document->recipe()));

    // Remove the mirror flakes.
    panel()->selectComponent(2);
    button("structure_remove_component")->click();
    QCOMPARE(componentNames(m_document->recipe(), kBase), (std::vector<std::string>{"pearl", "pigment"}));
    QCOMPARE(m_document->undoStack()->undoText(),
             QStringLiteral("Remove mirror flake 'mirror' from 'basecoat'"));
    QCOMPARE(table->rowCount(), 2);
    QCOMPARE(panel()->selectedComponent(), 1);                        // the last one left
    QVERIFY(m_dock->sliderFor("orientation_spread_deg") != nullptr);  // the pearl's still
    const Recipe removed = m_document->recipe();
    checkUndoRedo(before, removed);
    QCOMPARE(table->rowCount(), 3);
    // Past the end: refused, named.
    panel()->selectComponent(2);
    QVERIFY(!panel()->moveComponent(+1));
    QVERIFY2(panel()->message().contains("layers[1].components[2]: it is already the last component"),
             qPrintable(panel()->message()));
    QVERIFY(m_document->recipe() == before);
}

void RecipeStructureTest::anErrorTheRecipeAlreadyHadDoesNotBlockAMove() {
    // A slider can push the basecoat above 100 %: moving or renaming it (or
    // the other layer) keeps that error, it is not a new one.
    Recipe invalid = pearlescent();
    std::get<paintlab::Pigment>(invalid.layers[kBase].components[1]).volume_fraction = 0.99;
    QVERIFY(hasErrors(invalid));
    m_document->load(invalid, "test", 0);
    panel()->selectLayer(kBase);
    QVERIFY2(panel()->moveLayer(-1), qPrintable(panel()->message()));
    QVERIFY2(panel()->renameLayer(QStringLiteral("base")), qPrintable(panel()->message()));
    QCOMPARE(layerNames(m_document->recipe()), (std::vector<std::string>{"base", "layer"}));
    // Removing the offending pigment mends it.
    panel()->selectComponent(1);
    QVERIFY(panel()->removeComponent());
    QVERIFY(!hasErrors(m_document->recipe()));
    // A new error is still refused: the only layer, an empty name.
    QVERIFY(!panel()->renameLayer(QString()));
    QCOMPARE(m_document->undoStack()->count(), 3);
}

void RecipeStructureTest::openDepthProfileEditorsFollowTheirComponent() {
    auto section = [this](int layer, int component) {
        return m_dock->findChild<paintlab::gui::DepthProfileSection*>(
            QStringLiteral("depth_profile_section_%1_%2").arg(layer).arg(component));
    };
    QVERIFY(section(kBase, 0) != nullptr);
    section(kBase, 0)->setOpen(true);  // the pearl's
    // The pigment moves above the pearl, then the basecoat above the top layer:
    // the pearl's editor is open wherever the pearl is, and no other.
    panel()->selectLayer(kBase);
    panel()->selectComponent(1);
    QVERIFY(panel()->moveComponent(-1));
    QVERIFY(section(kBase, 1) != nullptr && section(kBase, 1)->isOpen());
    QVERIFY(!section(kBase, 0)->isOpen());
    QVERIFY(panel()->moveLayer(-1));
    QVERIFY(section(0, 1) != nullptr && section(0, 1)->isOpen());
    QVERIFY(!section(0, 0)->isOpen());
    QVERIFY(!section(0, 2)->isOpen());
    m_document->undoStack()->undo();
    m_document->undoStack()->undo();
    QVERIFY(section(kBase, 0)->isOpen());
    QVERIFY(!section(kBase, 1)->isOpen());
}

void RecipeStructureTest::theIngredientsDockAddsToTheSelectedLayer() {
    paintlab::gui::IngredientDock ingredients(m_document.get());
    QComboBox* layer = ingredients.layerChoice();
    QCOMPARE(layer->count(), 2);
    panel()->selectLayer(kBase);
    QCOMPARE(m_document->selectedLayer(), kBase);
    QCOMPARE(layer->currentIndex(), kBase);
    // After a layer is added above, the combo lists it and follows the selection.
    QVERIFY(panel()->addLayer());
    QCOMPARE(layer->count(), 3);
    QCOMPARE(layer->currentIndex(), kBase);
    QCOMPARE(layer->currentText(), QStringLiteral("2. clear coat"));
    panel()->selectLayer(0);
    QCOMPARE(layer->currentIndex(), 0);
    // And the other way: a layer chosen there is selected here, and stays
    // chosen through the next recipe change (an addition, an edit).
    layer->setCurrentIndex(2);
    emit layer->activated(2);
    QCOMPARE(panel()->selectedLayer(), 2);
    QCOMPARE(panel()->layerList()->currentRow(), 2);
    QVERIFY(panel()->componentTable()->rowCount() == 3);  // the basecoat's
    QVERIFY(panel()->moveLayer(-1));
    QCOMPARE(panel()->selectedLayer(), 1);
    QCOMPARE(layer->currentIndex(), 1);
    QCOMPARE(layer->currentText(), QStringLiteral("2. basecoat"));
}

void RecipeStructureTest::aStructureEditReachesTheRenderScheduler() {
    // As MainWindow::requestRender: every recipeChanged is a request.
    paintlab::gui::RenderScheduler scheduler;
    QObject::connect(m_document.get(), &RecipeDocument::recipeChanged, &scheduler,
                     [&](bool) { scheduler.request(m_document->recipe(), paintlab::Preset::Preview); });
    QSignalSpy finished(&scheduler, &paintlab::gui::RenderScheduler::finished);
    QSignalSpy failed(&scheduler, &paintlab::gui::RenderScheduler::failed);
    const quint64 before = scheduler.latestGeneration();
    panel()->selectLayer(kBase);
    panel()->selectComponent(0);
    QVERIFY(panel()->removeComponent());
    QCOMPARE(scheduler.latestGeneration(), before + 1);
    QTRY_VERIFY_WITH_TIMEOUT(finished.count() == 1, 20000);
    QCOMPARE(failed.count(), 0);
    const auto result = finished.at(0).at(0).value<paintlab::gui::RenderResult>();
    QCOMPARE(result.generation, before + 1);
    QVERIFY(result.brdf != nullptr);
    // Its undo is a request too.
    m_document->undoStack()->undo();
    QCOMPARE(scheduler.latestGeneration(), before + 2);
    QTRY_VERIFY_WITH_TIMEOUT(scheduler.idle(), 20000);
}

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    RecipeStructureTest test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_recipe_structure.moc"
