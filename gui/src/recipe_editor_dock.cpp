#include "recipe_editor_dock.h"

#include "depth_profile_edit.h"
#include "depth_profile_section.h"
#include "parameter_field.h"
#include "recipe_structure_panel.h"
#include "set_parameter_command.h"
#include "wheel_scrolls_form.h"

#include "paintlab/engine/io/number_format.h"

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

namespace {

constexpr int kTitleWidth = 240;  // pixels of a layer's or component's group title, at most

}  // namespace

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
    rebuild();
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

QLabel* RecipeEditorDock::messageFor(std::string_view key) const {
    for (const Row& row : m_rows)
        if (row.ref.decl->key == key) return row.message;
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
    if (!m_document->hasRecipe()) {
        // Until a recipe is loaded: what to do.
        auto* hint = new QLabel(tr("No recipe open: pick one in the Recipes list, or use File > Open recipe "
                                   "file..., to edit its layers and ingredients here."),
                                m_form);
        hint->setObjectName("editor_empty_hint");
        hint->setWordWrap(true);
        m_layout->addWidget(hint);
        m_layout->addStretch(1);
        return;
    }
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
                // "interference flake", not the code.
                const QString kind =
                    QString::fromUtf8(componentKind(c).data(), static_cast<int>(componentKind(c).size()))
                        .replace('_', ' ');
                title += QString::fromUtf8(" \u203a ") + QString::fromStdString(componentName(c)) + " (" +
                         kind + ")";
            }
            // A group box is at least as wide as its title: a long one is
            // shortened ("…"), whole in the tooltip, so the rows fit a narrow dock.
            auto* box = new QGroupBox(m_form);
            box->setTitle(box->fontMetrics().elidedText(title, Qt::ElideMiddle, kTitleWidth));
            box->setToolTip(title);
            grid = new QGridLayout(box);
            m_layout->addWidget(box);
        }
        const ParameterDecl& d = *ref.decl;
        const double value = *scalarField(recipe, ref);
        Row row{ref, sliderRange(d, value), nullptr, nullptr};
        const int line = grid->rowCount();
        auto* label = new QLabel(QString::fromUtf8(d.label.data(), static_cast<int>(d.label.size())), m_form);
        label->setToolTip(QString::fromUtf8(d.help.data(), static_cast<int>(d.help.size())));
        row.spin = new ParameterField(d, m_form);
        row.spin->setSingleStep((row.range.hi - row.range.lo) * displayUnit(d).scale / 100.0);
        row.spin->showValue(value);
        row.spin->setObjectName(QString::fromUtf8(d.key.data(), static_cast<int>(d.key.size())));
        row.spin->setToolTip(tr("Allowed %1 to %2; usual %3 to %4")
                                 .arg(QString::fromStdString(displayText(d, d.min)),
                                      QString::fromStdString(displayText(d, d.max)),
                                      QString::fromStdString(displayText(d, d.typicalMin)),
                                      QString::fromStdString(displayText(d, d.typicalMax))));
        row.slider = new QSlider(Qt::Horizontal, m_form);
        row.slider->setRange(0, kSliderSteps);
        letWheelScrollTheForm(row.slider);
        row.slider->setObjectName(row.spin->objectName() + "_slider");
        row.message = new QLabel(m_form);
        row.message->setObjectName(row.spin->objectName() + "_message");
        row.message->setWordWrap(true);
        row.message->hide();
        grid->addWidget(label, line, 0);
        grid->addWidget(row.spin, line, 1);
        grid->addWidget(row.slider, line, 2);
        grid->addWidget(row.message, line + 1, 0, 1, 3);
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
            // Rounded to 4 significant digits: a dragged value reads as a lab would write it.
            const double v = r->range.valueAt(static_cast<double>(step) / kSliderSteps);
            const double digits = std::pow(10.0, std::floor(std::log10(std::abs(v))) - 3.0);
            edit(*r, v > 0.0 ? std::round(v / digits) * digits : v, r->slider->isSliderDown());
            showMessage(*r, {}, false);
        });
        // The drag is over: the final, full-quality render of what it left.
        connect(row.slider, &QSlider::sliderReleased, m_document, &RecipeDocument::settle);
        connect(row.spin, &QDoubleSpinBox::editingFinished, this,
                [this, i = static_cast<std::size_t>(&row - m_rows.data())]() { commitTyped(m_rows[i]); });
    }
    refreshValues();
}

void RecipeEditorDock::refreshValues() {
    const Recipe& recipe = m_document->recipe();
    for (Row& row : m_rows) {
        const double* field = scalarField(recipe, row.ref);
        if (field == nullptr) continue;
        const QSignalBlocker block_slider(row.slider);
        // A message is about the value it was given for: another value (an undo) ends it.
        if (row.spin->recipeValue() != *field) showMessage(row, {}, false);
        row.spin->showValue(*field);
        // A logarithmic slider's left end stands for everything below it (0 included).
        if (*field > row.range.hi || (!row.range.log && *field < row.range.lo))
            row.range = sliderRange(*row.ref.decl, *field);
        row.slider->setValue(static_cast<int>(std::lround(row.range.position(*field) * kSliderSteps)));
    }
}

void RecipeEditorDock::showMessage(const Row& row, const QString& text, bool error) {
    row.message->setText(text);
    row.message->setStyleSheet(error ? QStringLiteral("QLabel { color: #b00020; }")
                                     : QStringLiteral("QLabel { color: #8a5a00; }"));
    row.message->setVisible(!text.isEmpty());
}

void RecipeEditorDock::commitTyped(Row& row) {
    const double* current = scalarField(m_document->recipe(), row.ref);
    if (current == nullptr) return;
    const ParameterDecl& decl = *row.ref.decl;
    QString typed = row.spin->typedText();
    // Nothing typed: the arrows or the wheel changed the value, or nothing did.
    if (typed.isEmpty()) {
        if (row.spin->cleanText() == row.spin->textFromValue(*current * displayUnit(decl).scale)) return;
        typed = QString::fromStdString(io::formatNumber(row.spin->value(), io::NumberFormat::Shortest));
    }
    const TypedValue checked = checkTypedValue(decl, typed.toStdString());
    const QString message = QString::fromStdString(checked.message);
    switch (checked.verdict) {
    case TypedValue::Verdict::NotANumber:
    case TypedValue::Verdict::Refuse:
        // The field goes back to the recipe's value and says why.
        row.spin->showValue(*current);
        showMessage(row, tr("%1; kept %2").arg(message, QString::fromStdString(displayText(decl, *current))),
                    true);
        return;
    case TypedValue::Verdict::ApplyWithWarning:
    case TypedValue::Verdict::Apply:
        break;
    }
    // The value shown as typed ("1e3" reads 1000 µm), and one undo step.
    row.spin->showValue(checked.value);
    edit(row, checked.value, false);
    showMessage(row, message, false);
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
