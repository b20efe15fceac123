#pragma once
// One edit of one scalar parameter, undoable. Consecutive edits of the same
// parameter (a slider being dragged) merge into one undo step, whose undo
// restores the value from before the drag exactly (the whole recipe is
// kept, not recomputed from a delta).

#include "recipe_document.h"
#include "recipe_parameters.h"

#include <QUndoCommand>

namespace paintlab::gui {

class SetParameterCommand : public QUndoCommand {
public:
    // Throws nothing; an out-of-range value is clamped to the declaration's range.
    SetParameterCommand(RecipeDocument* document, const ParameterRef& ref, double value, bool interactive);

    void undo() override;
    void redo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    static constexpr int kId = 0x504c;  // "PL"
    RecipeDocument* m_document;
    ParameterRef m_ref;
    Recipe m_before;
    Recipe m_after;
    bool m_interactive;
};

}  // namespace paintlab::gui
