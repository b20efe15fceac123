#include "set_parameter_command.h"

#include <QCoreApplication>

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

SetParameterCommand::SetParameterCommand(RecipeDocument* document, const ParameterRef& ref, double value,
                                         int drag, bool interactive)
    : m_document(document), m_ref(ref), m_drag(drag), m_before(document->recipe()),
      m_after(document->recipe()), m_interactive(interactive) {
    if (double* field = scalarField(m_after, ref)) {
        const ParameterDecl& decl = *ref.decl;
        *field = std::clamp(value, decl.min, decl.max);
        if (decl.minExclusive && *field <= decl.min) *field = std::nextafter(decl.min, decl.max);
    }
    setText(
        QCoreApplication::translate("SetParameterCommand", "Set %1").arg(QString::fromStdString(ref.label)));
}

void SetParameterCommand::undo() { m_document->applyEdit(m_before, false); }

void SetParameterCommand::redo() {
    // Interactive only when first done (during the drag); a redo is a final state.
    m_document->applyEdit(m_after, m_interactive);
    m_interactive = false;
}

bool SetParameterCommand::mergeWith(const QUndoCommand* other) {
    const auto* next = dynamic_cast<const SetParameterCommand*>(other);
    if (next == nullptr || m_drag == 0 || next->m_drag != m_drag || !(next->m_ref == m_ref)) return false;
    m_after = next->m_after;
    setObsolete(m_after == m_before);  // dragged back to where it began: no step
    return true;
}

}  // namespace paintlab::gui
