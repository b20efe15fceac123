#include "set_depth_profile_command.h"

#include "depth_profile_edit.h"

#include <QCoreApplication>

namespace paintlab::gui {

SetDepthProfileCommand::SetDepthProfileCommand(RecipeDocument* document, int layer, int component,
                                               const std::optional<DepthProfile>& profile, int drag,
                                               bool interactive)
    : m_document(document), m_layer(layer), m_component(component), m_drag(drag),
      m_before(document->recipe()), m_after(withProfile(document->recipe(), layer, component, profile)),
      m_interactive(interactive) {
    const Component& c =
        m_before.layers[static_cast<std::size_t>(layer)].components[static_cast<std::size_t>(component)];
    setText(profile ? QCoreApplication::translate("SetDepthProfileCommand", "Depth profile of %1")
                          .arg(QString::fromStdString(componentName(c)))
                    : QCoreApplication::translate("SetDepthProfileCommand", "Uniform depth profile of %1")
                          .arg(QString::fromStdString(componentName(c))));
}

void SetDepthProfileCommand::undo() { m_document->applyEdit(m_before, false); }

void SetDepthProfileCommand::redo() {
    // Interactive only when first done (during the drag); a redo is a final state.
    m_document->applyEdit(m_after, m_interactive);
    m_interactive = false;
}

bool SetDepthProfileCommand::mergeWith(const QUndoCommand* other) {
    const auto* next = dynamic_cast<const SetDepthProfileCommand*>(other);
    if (next == nullptr || m_drag == 0 || next->m_drag != m_drag || next->m_layer != m_layer ||
        next->m_component != m_component)
        return false;
    m_after = next->m_after;
    // Dragged back to where it started: QUndoStack drops the step.
    setObsolete(m_after == m_before);
    return true;
}

}  // namespace paintlab::gui
