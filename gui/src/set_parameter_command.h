#pragma once
// One edit of one scalar parameter, undoable. The edits of one slider drag
// (same drag number) merge into one undo step, whose undo restores the value
// from before the drag exactly (the whole recipe is kept, not recomputed
// from a delta); every other edit (a value typed, a key press on the slider)
// is a step of its own, and a drag that ends where it began leaves none.

#include "recipe_document.h"
#include "recipe_parameters.h"

#include <QUndoCommand>

namespace paintlab::gui {

class SetParameterCommand : public QUndoCommand {
public:
    // drag: 0 for a one-off edit, otherwise the number of the slider drag this
    // edit belongs to. interactive: sent while the slider is held (the render
    // may use the preview preset). Throws nothing; an out-of-range value is
    // clamped to the declaration's range.
    SetParameterCommand(RecipeDocument* document, const ParameterRef& ref, double value, int drag,
                        bool interactive);

    void undo() override;
    void redo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    static constexpr int kId = 0x504c;  // "PL"
    RecipeDocument* m_document;
    ParameterRef m_ref;
    int m_drag;
    Recipe m_before;
    Recipe m_after;
    bool m_interactive;
};

}  // namespace paintlab::gui
