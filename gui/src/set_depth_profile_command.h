#pragma once
// One undoable change of a component's depth profile (set, reshaped or
// removed). The edits of one node drag carry the same drag number and merge
// into one undo step, as a slider drag does (set_parameter_command.h); a drag
// that ends where it began leaves no step. The whole recipe before and after
// is kept, so undo restores the previous profile exactly.

#include "recipe_document.h"

#include "paintlab/engine/recipe.h"

#include <QUndoCommand>

#include <optional>

namespace paintlab::gui {

class SetDepthProfileCommand : public QUndoCommand {
public:
    // drag: 0 for a one-off edit (a preset, an added node), otherwise the
    // number of the drag this edit belongs to. interactive: sent while the
    // node is held (the render may use the preview preset).
    // The profile must have been checked (depth_profile_edit.h): this applies it as given.
    // Throws std::out_of_range if the component has no profile slot.
    SetDepthProfileCommand(RecipeDocument* document, int layer, int component,
                           const std::optional<DepthProfile>& profile, int drag, bool interactive);

    void undo() override;
    void redo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    static constexpr int kId = 0x5044;  // "PD"
    RecipeDocument* m_document;
    int m_layer;
    int m_component;
    int m_drag;
    Recipe m_before;
    Recipe m_after;
    bool m_interactive;
};

}  // namespace paintlab::gui
