#include "recipe_structure_panel.h"

#include "replace_recipe_command.h"

#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>
#include <utility>

namespace paintlab::gui {

namespace {

QString qs(std::string_view text) {
    return QString::fromUtf8(text.data(), static_cast<qsizetype>(text.size()));
}

// Room for four rows: the usual paint has two to four layers and components.
constexpr int kListHeight = 76;
constexpr int kTableHeight = 104;

}  // namespace

RecipeStructurePanel::RecipeStructurePanel(RecipeDocument* document, QWidget* parent)
    : QWidget(parent), m_document(document) {
    setObjectName("recipe_structure");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);

    auto* layer_box = new QGroupBox(tr("Layers (top coat first)"), this);
    auto* layer_layout = new QVBoxLayout(layer_box);
    m_layers = new QListWidget(layer_box);
    m_layers->setObjectName("structure_layers");
    m_layers->setFixedHeight(kListHeight);
    m_layers->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
    m_layers->setToolTip(tr("Double-click a layer to rename it"));
    layer_layout->addWidget(m_layers);
    // The buttons below the list: the dock is narrow and its rows are wide already.
    auto* layer_buttons = new QHBoxLayout;
    m_add_layer = button("structure_add_layer", tr("Add"),
                         tr("Add a clear lacquer above the selected layer (the first layer's binder)"));
    m_remove_layer = button("structure_remove_layer", tr("Remove"), tr("Remove the selected layer"));
    m_layer_up =
        button("structure_layer_up", tr("Up"), tr("Move the selected layer up, towards the top coat"));
    m_layer_down =
        button("structure_layer_down", tr("Down"), tr("Move the selected layer down, towards the substrate"));
    m_rename_layer = button("structure_rename_layer", tr("Rename"), tr("Rename the selected layer"));
    for (QToolButton* b : {m_add_layer, m_remove_layer, m_layer_up, m_layer_down, m_rename_layer})
        layer_buttons->addWidget(b);
    layer_buttons->addStretch(1);
    layer_layout->addLayout(layer_buttons);
    layout->addWidget(layer_box);

    m_component_box = new QGroupBox(this);
    auto* component_layout = new QVBoxLayout(m_component_box);
    m_components = new QTableWidget(0, 3, m_component_box);
    m_components->setObjectName("structure_components");
    m_components->setHorizontalHeaderLabels({tr("Name"), tr("Kind"), tr("Volume fraction")});
    m_components->setFixedHeight(kTableHeight);
    m_components->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_components->setSelectionMode(QAbstractItemView::SingleSelection);
    m_components->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_components->verticalHeader()->setVisible(false);
    m_components->verticalHeader()->setDefaultSectionSize(m_components->fontMetrics().height() + 6);
    m_components->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
    m_components->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
    m_components->horizontalHeader()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
    m_components->setToolTip(tr("Components are added from the Ingredients dock (Add to layer)"));
    component_layout->addWidget(m_components);
    auto* component_buttons = new QHBoxLayout;
    m_remove_component = button("structure_remove_component", tr("Remove"),
                                tr("Remove the selected component from the layer"));
    m_component_up = button("structure_component_up", tr("Up"), tr("Move the selected component up"));
    m_component_down = button("structure_component_down", tr("Down"), tr("Move the selected component down"));
    for (QToolButton* b : {m_remove_component, m_component_up, m_component_down})
        component_buttons->addWidget(b);
    component_buttons->addStretch(1);
    component_layout->addLayout(component_buttons);
    layout->addWidget(m_component_box);

    m_message = new QLabel(this);
    m_message->setObjectName("structure_message");
    m_message->setWordWrap(true);
    m_message->setStyleSheet("color: #d62728;");
    m_message->hide();
    layout->addWidget(m_message);

    connect(m_layers, &QListWidget::currentRowChanged, this, [this](int row) {
        if (!m_filling) selectLayer(row);
    });
    connect(m_layers, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
        if (m_filling) return;
        // After the item's editor has finished committing: the rename refills the list.
        const int row = m_layers->row(item);
        const QString name = item->text();
        QMetaObject::invokeMethod(
            this,
            [this, row, name]() {
                selectLayer(row);
                renameLayer(name);
            },
            Qt::QueuedConnection);
    });
    connect(m_components, &QTableWidget::currentCellChanged, this, [this](int row) {
        if (!m_filling) selectComponent(row);
    });
    connect(m_add_layer, &QToolButton::clicked, this, [this]() { addLayer(); });
    connect(m_remove_layer, &QToolButton::clicked, this, [this]() { removeLayer(); });
    connect(m_layer_up, &QToolButton::clicked, this, [this]() { moveLayer(-1); });
    connect(m_layer_down, &QToolButton::clicked, this, [this]() { moveLayer(+1); });
    connect(m_rename_layer, &QToolButton::clicked, this, [this]() {
        if (QListWidgetItem* item = m_layers->currentItem()) m_layers->editItem(item);
    });
    connect(m_remove_component, &QToolButton::clicked, this, [this]() { removeComponent(); });
    connect(m_component_up, &QToolButton::clicked, this, [this]() { moveComponent(-1); });
    connect(m_component_down, &QToolButton::clicked, this, [this]() { moveComponent(+1); });
    connect(document, &RecipeDocument::recipeChanged, this, &RecipeStructurePanel::refresh);
    // The layer chosen in the Ingredients dock.
    connect(document, &RecipeDocument::selectedLayerChanged, this, [this](int layer) {
        if (layer != m_layer) selectLayer(layer);
    });
    connect(document, &RecipeDocument::recipeLoaded, this, [this]() {
        m_layer = 0;
        m_component = -1;
        m_message->clear();
        m_message->hide();
        refresh();
    });
    refresh();
}

QToolButton* RecipeStructurePanel::button(const QString& name, const QString& text, const QString& tip) {
    auto* b = new QToolButton(this);
    b->setObjectName(name);
    b->setText(text);
    b->setToolTip(tip);
    return b;
}

void RecipeStructurePanel::selectLayer(int layer) {
    const int count = m_document->hasRecipe() ? static_cast<int>(m_document->recipe().layers.size()) : 0;
    if (layer < 0 || layer >= count) return;
    if (layer != m_layer) m_component = -1;
    m_layer = layer;
    if (m_layers->currentRow() != layer) {
        m_filling = true;
        m_layers->setCurrentRow(layer);
        m_filling = false;
    }
    fillComponents();
    m_document->setSelectedLayer(m_layer);
    updateButtons();
}

void RecipeStructurePanel::selectComponent(int component) {
    if (m_layer < 0 || !m_document->hasRecipe()) return;
    const auto& components = m_document->recipe().layers[static_cast<std::size_t>(m_layer)].components;
    if (component < -1 || component >= static_cast<int>(components.size())) return;
    m_component = component;
    if (m_components->currentRow() != component) {
        m_filling = true;
        m_components->selectRow(component);
        m_filling = false;
    }
    updateButtons();
}

bool RecipeStructurePanel::apply(const std::function<StructureEdit(const Recipe&)>& make, int layer,
                                 int component) {
    if (!m_document->hasRecipe()) return false;
    try {
        const Recipe& current = m_document->recipe();
        StructureEdit edit = make(current);
        checkStructureEdit(current, edit.recipe);
        m_message->clear();
        m_message->hide();
        // Selected in the refresh that the push's recipeChanged brings.
        m_layer = layer;
        m_component = component;
        m_document->undoStack()->push(
            new ReplaceRecipeCommand(m_document, std::move(edit.recipe), QString::fromStdString(edit.text)));
        return true;
    } catch (const std::exception& e) {
        m_message->setText(tr("Not applied: %1").arg(QString::fromUtf8(e.what())));
        m_message->show();
        refresh();  // a refused rename shows the old name again
        return false;
    }
}

bool RecipeStructurePanel::addLayer() {
    const int at = std::max(m_layer, 0);
    return apply([at](const Recipe& r) { return withLayerAdded(r, at); }, at, -1);
}

bool RecipeStructurePanel::removeLayer() {
    const int layer = m_layer;
    return apply([layer](const Recipe& r) { return withLayerRemoved(r, layer); }, std::max(layer - 1, 0), -1);
}

bool RecipeStructurePanel::moveLayer(int delta) {
    const int layer = m_layer;
    const int to = layer + delta;
    return apply([layer, to](const Recipe& r) { return withLayerMoved(r, layer, to); }, to, m_component);
}

bool RecipeStructurePanel::renameLayer(const QString& name) {
    const int layer = m_layer;
    const std::string text = name.toStdString();
    if (m_document->hasRecipe() && layer >= 0 &&
        layer < static_cast<int>(m_document->recipe().layers.size()) &&
        m_document->recipe().layers[static_cast<std::size_t>(layer)].name == text)
        return false;  // unchanged: no empty undo step
    return apply([layer, text](const Recipe& r) { return withLayerRenamed(r, layer, text); }, layer,
                 m_component);
}

bool RecipeStructurePanel::removeComponent() {
    const int layer = m_layer;
    const int component = m_component;
    return apply([layer, component](const Recipe& r) { return withComponentRemoved(r, layer, component); },
                 layer, component);
}

bool RecipeStructurePanel::moveComponent(int delta) {
    const int layer = m_layer;
    const int component = m_component;
    const int to = component + delta;
    return apply(
        [layer, component, to](const Recipe& r) { return withComponentMoved(r, layer, component, to); },
        layer, to);
}

QString RecipeStructurePanel::message() const { return m_message->text(); }

void RecipeStructurePanel::refresh() {
    m_filling = true;
    m_layers->clear();
    const int count = m_document->hasRecipe() ? static_cast<int>(m_document->recipe().layers.size()) : 0;
    if (m_document->hasRecipe())
        for (const Layer& layer : m_document->recipe().layers) {
            auto* item = new QListWidgetItem(QString::fromStdString(layer.name), m_layers);
            item->setFlags(item->flags() | Qt::ItemIsEditable);
            item->setToolTip(tr("%1 µm, %n component(s)", nullptr, static_cast<int>(layer.components.size()))
                                 .arg(layer.thickness_um));
        }
    m_layer = count == 0 ? -1 : std::clamp(m_layer, 0, count - 1);
    m_layers->setCurrentRow(m_layer);
    m_filling = false;
    fillComponents();
    m_document->setSelectedLayer(m_layer);
    updateButtons();
}

void RecipeStructurePanel::fillComponents() {
    m_filling = true;
    m_components->clearContents();
    m_components->setRowCount(0);
    if (m_layer < 0 || !m_document->hasRecipe()) {
        m_component_box->setTitle(tr("Components"));
        m_component = -1;
        m_filling = false;
        return;
    }
    const Layer& layer = m_document->recipe().layers[static_cast<std::size_t>(m_layer)];
    m_component_box->setTitle(tr("Components of '%1'").arg(QString::fromStdString(layer.name)));
    const int count = static_cast<int>(layer.components.size());
    m_components->setRowCount(count);
    for (int row = 0; row < count; ++row) {
        const Component& c = layer.components[static_cast<std::size_t>(row)];
        QString kind = qs(componentKind(c));
        kind.replace('_', ' ');
        // A raw medium has no concentration: it fills the layer.
        const QString fraction =
            std::holds_alternative<RawMedium>(c)
                ? tr("fills the layer")
                : QStringLiteral("%1 %").arg(100.0 * componentVolumeFraction(c), 0, 'g', 4);
        m_components->setItem(row, 0, new QTableWidgetItem(QString::fromStdString(componentName(c))));
        m_components->setItem(row, 1, new QTableWidgetItem(kind));
        auto* value = new QTableWidgetItem(fraction);
        value->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        m_components->setItem(row, 2, value);
    }
    m_component = std::min(m_component, count - 1);
    if (m_component >= 0) m_components->selectRow(m_component);
    m_filling = false;
}

void RecipeStructurePanel::updateButtons() {
    const bool has = m_document->hasRecipe();
    const int layers = has ? static_cast<int>(m_document->recipe().layers.size()) : 0;
    const int components =
        has && m_layer >= 0
            ? static_cast<int>(
                  m_document->recipe().layers[static_cast<std::size_t>(m_layer)].components.size())
            : 0;
    m_add_layer->setEnabled(has);
    m_remove_layer->setEnabled(layers > 1 && m_layer >= 0);  // a paint keeps at least one layer
    m_layer_up->setEnabled(m_layer > 0);
    m_layer_down->setEnabled(m_layer >= 0 && m_layer < layers - 1);
    m_rename_layer->setEnabled(m_layer >= 0);
    m_remove_component->setEnabled(m_component >= 0);
    m_component_up->setEnabled(m_component > 0);
    m_component_down->setEnabled(m_component >= 0 && m_component < components - 1);
}

}  // namespace paintlab::gui
