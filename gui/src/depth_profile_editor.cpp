#include "depth_profile_editor.h"

#include "depth_profile_plot.h"
#include "set_depth_profile_command.h"

#include "paintlab/engine/recipe_paths.h"

#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QUndoStack>
#include <QVBoxLayout>

namespace paintlab::gui {

namespace {

struct PresetEntry {
    DepthProfilePreset preset;
    const char* label;
};
constexpr PresetEntry kPresets[] = {
    {DepthProfilePreset::Uniform, QT_TRANSLATE_NOOP("DepthProfileEditor", "Uniform")},
    {DepthProfilePreset::EnrichedTop, QT_TRANSLATE_NOOP("DepthProfileEditor", "Enriched at the top")},
    {DepthProfilePreset::Settled,
     QT_TRANSLATE_NOOP("DepthProfileEditor", "Settled (enriched at the bottom)")},
    {DepthProfilePreset::LinearGradient,
     QT_TRANSLATE_NOOP("DepthProfileEditor", "Linear gradient (0.5 at the top to 1.5 at the bottom)")},
};

QString number(double value) { return QString::number(value, 'g', 6); }

}  // namespace

DepthProfileEditor::DepthProfileEditor(RecipeDocument* document, int layer, int component, QWidget* parent)
    : QWidget(parent), m_document(document), m_layer(layer), m_component(component) {
    setObjectName("depth_profile_editor");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    m_title = new QLabel(this);
    m_title->setObjectName("depth_profile_title");
    m_plot = new DepthProfilePlot(this);
    m_plot->setMinimumHeight(200);  // room to place a node to a few percent of the weight axis
    layout->addWidget(m_title);
    layout->addWidget(m_plot, 1);

    auto* buttons = new QHBoxLayout;
    m_presets = new QComboBox(this);
    m_presets->setObjectName("depth_profile_presets");
    m_presets->addItem(tr("Preset..."));
    for (const PresetEntry& entry : kPresets) m_presets->addItem(tr(entry.label));
    m_presets->setToolTip(tr("Replace the profile by a typical shape (one undo step)"));
    m_uniform = new QPushButton(tr("Uniform"), this);
    m_uniform->setObjectName("depth_profile_uniform");
    m_uniform->setToolTip(tr("Remove the profile: the same concentration at every depth"));
    buttons->addWidget(m_presets, 1);
    buttons->addWidget(m_uniform);
    layout->addLayout(buttons);

    auto* node = new QGridLayout;
    m_node = new QLabel(this);
    m_depth = new QLineEdit(this);
    m_depth->setObjectName("depth_profile_node_depth");
    m_depth->setToolTip(tr("Relative depth of the selected node: 0 = top of the layer, 1 = bottom"));
    m_weight = new QLineEdit(this);
    m_weight->setObjectName("depth_profile_node_weight");
    m_weight->setToolTip(tr("Weight of the selected node (>= 0): the shape of the concentration"));
    node->addWidget(m_node, 0, 0);
    node->addWidget(new QLabel(tr("depth"), this), 0, 1);
    node->addWidget(m_depth, 0, 2);
    node->addWidget(new QLabel(tr("weight"), this), 0, 3);
    node->addWidget(m_weight, 0, 4);
    layout->addLayout(node);

    m_statistics = new QLabel(this);
    m_statistics->setObjectName("depth_profile_statistics");
    m_message = new QLabel(this);
    m_message->setObjectName("depth_profile_message");
    m_message->setWordWrap(true);
    m_message->setStyleSheet("color: #d62728;");
    layout->addWidget(m_statistics);
    layout->addWidget(m_message);

    connect(m_plot, &DepthProfilePlot::nodeDragged, this, [this](const DepthProfile& profile) {
        if (m_drag == 0) {
            m_drag = RecipeDocument::nextDragNumber();
            m_drag_pushed = false;
        }
        propose(profile, m_drag, true);
    });
    connect(m_plot, &DepthProfilePlot::dragReleased, this, [this](const DepthProfile& profile) {
        if (m_drag != 0) propose(profile, m_drag, false);
        m_drag = 0;
        m_drag_pushed = false;
    });
    connect(m_plot, &DepthProfilePlot::edited, this, [this](const DepthProfile& profile) { apply(profile); });
    connect(m_plot, &DepthProfilePlot::refused, this, &DepthProfileEditor::refuse);
    connect(m_plot, &DepthProfilePlot::selectionChanged, this, &DepthProfileEditor::showNode);
    connect(m_presets, &QComboBox::activated, this, [this](int index) {
        if (index > 0) applyPreset(kPresets[index - 1].preset);
        const QSignalBlocker block(m_presets);
        m_presets->setCurrentIndex(0);  // a command, not a state: the chart shows the result
    });
    connect(m_uniform, &QPushButton::clicked, this, [this]() { apply(std::nullopt); });
    connect(m_depth, &QLineEdit::editingFinished, this, [this]() { editNode(true); });
    connect(m_weight, &QLineEdit::editingFinished, this, [this]() { editNode(false); });
    connect(document, &RecipeDocument::recipeChanged, this, &DepthProfileEditor::refresh);
    refresh();
}

const std::optional<DepthProfile>* DepthProfileEditor::stored() const {
    return componentProfile(m_document->recipe(), m_layer, m_component);
}

QString DepthProfileEditor::message() const { return m_message->text(); }

QString DepthProfileEditor::statistics() const { return m_statistics->text(); }

bool DepthProfileEditor::apply(const std::optional<DepthProfile>& profile) {
    return propose(profile, 0, false);
}

bool DepthProfileEditor::applyPreset(DepthProfilePreset preset) {
    // The uniform preset is the absence of a profile (the engine treats both alike).
    if (preset == DepthProfilePreset::Uniform) return apply(std::nullopt);
    return apply(presetProfile(preset));
}

bool DepthProfileEditor::propose(const std::optional<DepthProfile>& profile, int drag, bool interactive) {
    if (stored() == nullptr) {
        refuse(tr("this component is no longer in the recipe"));
        return false;
    }
    if (profile) {
        const std::string problem = depthProfileProblem(*profile);
        if (!problem.empty()) {
            refuse(QString::fromStdString(problem));
            return false;
        }
    }
    const Recipe& current = m_document->recipe();
    const Recipe candidate = withProfile(current, m_layer, m_component, profile);
    if (candidate == current) {
        // A drag let go where its last edit left it: announce the recipe again
        // as final (full-quality render), as a released slider does.
        // The last refusal, if any, still stands (a drag stopped at the all-zero state).
        if (drag != 0 && !interactive && m_drag_pushed) m_document->settle();
        return true;
    }
    const std::string problem = profileEditError(current, candidate, m_layer);
    if (!problem.empty()) {
        refuse(QString::fromStdString(problem));
        return false;
    }
    m_message->clear();
    if (drag != 0) m_drag_pushed = true;
    m_document->undoStack()->push(
        new SetDepthProfileCommand(m_document, m_layer, m_component, profile, drag, interactive));
    return true;
}

void DepthProfileEditor::refuse(const QString& reason) {
    m_message->setText(tr("Not applied: %1").arg(reason));
    refresh();  // the chart and fields show the recipe's profile again
}

void DepthProfileEditor::refresh() {
    const std::optional<DepthProfile>* slot = stored();
    setEnabled(slot != nullptr);
    if (slot == nullptr) return;
    const Layer& layer = m_document->recipe().layers[static_cast<std::size_t>(m_layer)];
    const Component& component = layer.components[static_cast<std::size_t>(m_component)];
    m_title->setText(
        tr("Depth profile of %1 in %2 (%3 µm)")
            .arg(QString::fromStdString(componentName(component)), QString::fromStdString(layer.name))
            .arg(layer.thickness_um, 0, 'g', 4));
    const DepthProfile shown = shownProfile(*slot);
    m_plot->setThicknessUm(layer.thickness_um);
    m_plot->setProfile(shown, slot->has_value());
    const double peak = shown.peakRelativeConcentration();
    m_statistics->setText(tr("mean weight %1 \u00b7 peak relative concentration %2 \u00d7 (peak volume "
                             "fraction %3 %)%4")
                              .arg(number(shown.meanWeight()), number(peak))
                              .arg(100.0 * componentVolumeFraction(component) * peak, 0, 'g', 4)
                              .arg(slot->has_value() ? QString() : tr(" \u00b7 uniform, no profile stored")));
    m_uniform->setEnabled(slot->has_value());
    showNode(m_plot->selectedNode());
}

void DepthProfileEditor::showNode(int node) {
    const DepthProfile& shown = m_plot->profile();
    const bool valid = node >= 0 && node < static_cast<int>(shown.depth.size());
    m_depth->setEnabled(valid);
    m_weight->setEnabled(valid);
    if (!valid) {
        m_node->setText(tr("no node selected"));
        m_depth->clear();
        m_weight->clear();
        return;
    }
    const auto i = static_cast<std::size_t>(node);
    const bool end = i == 0 || i + 1 == shown.depth.size();
    m_node->setText(tr("node %1 of %2").arg(node + 1).arg(shown.depth.size()));
    // The end nodes stay at the top and the bottom of the layer.
    m_depth->setReadOnly(end);
    m_depth->setText(number(shown.depth[i]));
    m_weight->setText(number(shown.weight[i]));
}

void DepthProfileEditor::editNode(bool depth_field) {
    const int node = m_plot->selectedNode();
    DepthProfile profile = m_plot->profile();
    if (node < 0 || node >= static_cast<int>(profile.depth.size())) return;
    const auto i = static_cast<std::size_t>(node);
    QLineEdit* field = depth_field ? m_depth : m_weight;
    bool ok = false;
    const double value = field->text().trimmed().toDouble(&ok);
    if (!ok) {
        refuse(tr("%1: '%2' is not a number")
                   .arg(QString::fromStdString(
                       elementPath("depth_profile", depth_field ? "depth" : "weight", i)))
                   .arg(field->text()));
        return;
    }
    (depth_field ? profile.depth : profile.weight)[i] = value;
    if (profile == m_plot->profile()) return;  // focus left the field without a change
    // Typed values are not clipped: a depth past a neighbour or a negative
    // weight is refused with its reason rather than silently moved.
    apply(profile);
}

}  // namespace paintlab::gui
