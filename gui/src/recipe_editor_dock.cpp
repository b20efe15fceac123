#include "recipe_editor_dock.h"

#include "depth_profile_edit.h"
#include "depth_profile_section.h"
#include "recipe_structure_panel.h"
#include "set_parameter_command.h"

#include <QDoubleSpinBox>
#include <QEvent>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace paintlab::gui {

RecipeEditorDock::RecipeEditorDock(RecipeDocument* document, QWidget* parent)
    : QDockWidget(tr("Recipe editor"), parent), m_document(document) {
    setObjectName("recipe_editor");
    auto* scroll = new QScrollArea(this);
    scroll->setWidgetResizable(true);
    // The layer list and component table above the parameter rows, which rebuild below it.
    auto* content = new QWidget(scroll);
    auto* content_layout = new QVBoxLayout(content);
    m_structure = new RecipeStructurePanel(document, content);
    // As wide as the view, not as the rows (their titles can be wider than
    // the dock): its buttons and columns stay in sight. See eventFilter.
    content_layout->addWidget(m_structure, 0, Qt::AlignLeft);
    m_content_margins = content_layout->contentsMargins().left() + content_layout->contentsMargins().right();
    scroll->viewport()->installEventFilter(this);
    m_form = new QWidget(content);
    m_layout = new QVBoxLayout(m_form);
    m_layout->setContentsMargins(0, 0, 0, 0);
    content_layout->addWidget(m_form, 1);
    scroll->setWidget(content);
    setWidget(scroll);
    connect(document, &RecipeDocument::recipeLoaded, this, &RecipeEditorDock::rebuild);
    connect(document, &RecipeDocument::recipeChanged, this, [this]() {
        // An edit that added, removed, moved or renamed a layer or component (or
        // its undo) changes the rows or their titles.
        if (structureChanged()) {
            rebuild();
        } else {
            refreshValues();
        }
    });
}

RecipeEditorDock::Shape RecipeEditorDock::shapeOf(const Recipe& recipe) {
    Shape shape;
    for (const Layer& layer : recipe.layers) {
        std::vector<std::string> components;
        for (const Component& c : layer.components)
            components.push_back(std::string(componentKind(c)) + " " + componentName(c));
        shape.emplace_back(layer.name, std::move(components));
    }
    return shape;
}

bool RecipeEditorDock::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() == QEvent::Resize)
        if (auto* viewport = qobject_cast<QWidget*>(watched))
            m_structure->setFixedWidth(std::max(viewport->width() - m_content_margins, 0));
    return QDockWidget::eventFilter(watched, event);
}

bool RecipeEditorDock::structureChanged() const {
    if (shapeOf(m_document->recipe()) != m_shape) return true;
    const std::vector<ParameterRef> refs = editableParameters(m_document->recipe());
    if (refs.size() != m_rows.size()) return true;
    for (std::size_t i = 0; i < refs.size(); ++i)
        if (!(refs[i] == m_rows[i].ref)) return true;
    return false;
}

QSlider* RecipeEditorDock::sliderFor(std::string_view key) const {
    for (const Row& row : m_rows)
        if (row.ref.decl->key == key) return row.slider;
    return nullptr;
}

void RecipeEditorDock::rebuild() {
    // Open depth-profile editors stay open, found by layer and component name
    // in the recipe shown until now (a component added, removed or moved, a
    // layer moved, keeps the others open).
    std::set<std::pair<std::string, std::string>> open_profiles;
    for (const auto* section : m_form->findChildren<DepthProfileSection*>()) {
        const auto layer = static_cast<std::size_t>(section->layer());
        const auto component = static_cast<std::size_t>(section->component());
        if (section->isOpen() && layer < m_shape.size() && component < m_shape[layer].second.size())
            open_profiles.insert({m_shape[layer].first, m_shape[layer].second[component]});
    }
    while (QLayoutItem* item = m_layout->takeAt(0)) {
        delete item->widget();
        delete item;
    }
    m_rows.clear();
    const Recipe& recipe = m_document->recipe();
    m_shape = shapeOf(recipe);
    // One group per layer / component, in recipe order.
    std::map<std::pair<int, int>, QGridLayout*> groups;
    for (const ParameterRef& ref : editableParameters(recipe)) {
        QGridLayout*& grid = groups[{ref.layer, ref.component}];
        if (grid == nullptr) {
            const Layer& layer = recipe.layers[static_cast<std::size_t>(ref.layer)];
            QString title = QString::fromStdString(layer.name);
            if (ref.component >= 0) {
                const Component& c = layer.components[static_cast<std::size_t>(ref.component)];
                title +=
                    QString::fromUtf8(" \u203a ") + QString::fromStdString(componentName(c)) + " (" +
                    QString::fromUtf8(componentKind(c).data(), static_cast<int>(componentKind(c).size())) +
                    ")";
            }
            auto* box = new QGroupBox(title, m_form);
            grid = new QGridLayout(box);
            m_layout->addWidget(box);
        }
        const ParameterDecl& d = *ref.decl;
        const double value = *scalarField(recipe, ref);
        Row row{ref, sliderRange(d, value), nullptr, nullptr};
        const int line = grid->rowCount();
        auto* label = new QLabel(QString::fromUtf8(d.label.data(), static_cast<int>(d.label.size())), m_form);
        label->setToolTip(QString::fromUtf8(d.help.data(), static_cast<int>(d.help.size())));
        row.spin = new QDoubleSpinBox(m_form);
        row.spin->setDecimals(4);
        row.spin->setRange(d.min, d.max);
        row.spin->setSingleStep((row.range.hi - row.range.lo) / 100.0);
        if (d.unit != "1")
            row.spin->setSuffix(" " + QString::fromUtf8(d.unit.data(), static_cast<int>(d.unit.size())));
        row.spin->setValue(value);
        row.spin->setObjectName(QString::fromUtf8(d.key.data(), static_cast<int>(d.key.size())));
        row.slider = new QSlider(Qt::Horizontal, m_form);
        row.slider->setRange(0, kSliderSteps);
        row.slider->setObjectName(row.spin->objectName() + "_slider");
        grid->addWidget(label, line, 0);
        grid->addWidget(row.spin, line, 1);
        grid->addWidget(row.slider, line, 2);
        m_rows.push_back(row);
    }
    // Below the rows of each pigment or flake: its depth-profile editor, opened on demand.
    for (const auto& [where, grid] : groups)
        if (where.second >= 0 && componentProfile(recipe, where.first, where.second) != nullptr) {
            auto* section = new DepthProfileSection(m_document, where.first, where.second, m_form);
            const auto& [layer_name, components] = m_shape[static_cast<std::size_t>(where.first)];
            section->setOpen(
                open_profiles.count({layer_name, components[static_cast<std::size_t>(where.second)]}) > 0);
            grid->addWidget(section, grid->rowCount(), 0, 1, 3);
        }
    m_layout->addStretch(1);
    // Connections after the rows exist: the vector no longer moves until the
    // next rebuild, which deletes these widgets (and their connections) first.
    for (const Row& row : m_rows) {
        const Row* r = &row;
        // A new drag number per press: the edits of one drag merge into one undo step.
        connect(row.slider, &QSlider::sliderPressed, this,
                [this]() { m_drag = RecipeDocument::nextDragNumber(); });
        connect(row.slider, &QSlider::valueChanged, this, [this, r](int step) {
            const double v = r->range.lo + (r->range.hi - r->range.lo) * step / kSliderSteps;
            edit(*r, v, r->slider->isSliderDown());
        });
        // The drag is over: the final, full-quality render of what it left.
        connect(row.slider, &QSlider::sliderReleased, m_document, &RecipeDocument::settle);
        connect(row.spin, &QDoubleSpinBox::editingFinished, this,
                [this, r]() { edit(*r, r->spin->value(), false); });
    }
    refreshValues();
}

void RecipeEditorDock::refreshValues() {
    const Recipe& recipe = m_document->recipe();
    for (Row& row : m_rows) {
        const double* field = scalarField(recipe, row.ref);
        if (field == nullptr) continue;
        const QSignalBlocker block_spin(row.spin);
        const QSignalBlocker block_slider(row.slider);
        row.spin->setValue(*field);
        if (*field < row.range.lo || *field > row.range.hi) row.range = sliderRange(*row.ref.decl, *field);
        const double t = (*field - row.range.lo) / (row.range.hi - row.range.lo);
        row.slider->setValue(static_cast<int>(std::lround(t * kSliderSteps)));
    }
}

void RecipeEditorDock::edit(const Row& row, double value, bool interactive) {
    const double* current = scalarField(m_document->recipe(), row.ref);
    if (current == nullptr) return;
    if (*current == value) return;  // nothing moved: no empty undo step
    // Held slider: part of the current drag; anything else (a typed value, a
    // key press on the slider) is one undo step of its own.
    const int drag = interactive ? m_drag : 0;
    m_document->undoStack()->push(new SetParameterCommand(m_document, row.ref, value, drag, interactive));
}

}  // namespace paintlab::gui
