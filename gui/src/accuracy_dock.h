#pragma once
// What accuracy costs in time, made visible: the preset policy, whether the
// effect plan is followed, the plan itself (each decision with what it runs,
// the error it accepts and why), the measured time of the last recompute and
// the colour error each preset is known to accept (measured against the
// converged reference preset on the demo paints, docs/PERFORMANCE.md).
//
// On top, one verdict a technician can act on, from the same numbers as the
// details below it (the plan's accepted errors added, against the preset's
// tolerance): "within ΔE00 x of the converged model", or what stands in the
// way, and where the fast model's own limit is the cause (model_validity.h:
// its worst multi-angle geometry), a button that runs the full model.

#include "render_scheduler.h"

#include <QDockWidget>

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace paintlab::gui {

class AccuracyDock : public QDockWidget {
    Q_OBJECT
public:
    explicit AccuracyDock(QWidget* parent = nullptr);

    // The preset for an edit: automatic = preview while a slider is dragged,
    // standard otherwise; or the one chosen.
    Preset presetFor(bool interactive) const;
    // "Follow the effect plan" (default) or the plain preset.
    bool followPlan() const;
    void setFollowPlan(bool follow);
    // recipe: the one the result was computed for (nullptr: unknown; the
    // verdict then cannot name the fast model's worst geometry).
    void showResult(const RenderResult& result, const Recipe* recipe = nullptr);
    // Nothing to judge: no recipe is open.
    void showNoRecipe();

    QTableWidget* planTable() const { return m_plan_table; }
    QLabel* planSummary() const { return m_plan_summary; }
    QLabel* verdict() const { return m_verdict; }
    // Shown when the verdict advises the full model.
    QPushButton* fullModelButton() const { return m_run_full; }

signals:
    void policyChanged();
    // "Compare with the full model" under the verdict.
    void fullModelRequested();

private:
    void showPlan(const RenderResult& result, const Recipe* recipe);
    void setVerdict(const QString& text, bool ok, bool advise_full_model);

    QLabel* m_verdict = nullptr;
    QPushButton* m_run_full = nullptr;
    QComboBox* m_policy = nullptr;
    QCheckBox* m_follow_plan = nullptr;
    QLabel* m_plan_summary = nullptr;
    QTableWidget* m_plan_table = nullptr;
    QLabel* m_last = nullptr;
};

}  // namespace paintlab::gui
