#pragma once
// What accuracy costs in time, made visible: the preset policy, whether the
// effect plan is followed, the plan itself (each decision with what it runs,
// the error it accepts and why), the measured time of the last recompute and
// the colour error each preset is known to accept (measured against the
// converged reference preset on the demo paints, docs/PERFORMANCE.md).

#include "render_scheduler.h"

#include <QDockWidget>

class QCheckBox;
class QComboBox;
class QLabel;
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
    void showResult(const RenderResult& result);

    QTableWidget* planTable() const { return m_plan_table; }
    QLabel* planSummary() const { return m_plan_summary; }

signals:
    void policyChanged();

private:
    void showPlan(const RenderResult& result);

    QComboBox* m_policy = nullptr;
    QCheckBox* m_follow_plan = nullptr;
    QLabel* m_plan_summary = nullptr;
    QTableWidget* m_plan_table = nullptr;
    QLabel* m_last = nullptr;
};

}  // namespace paintlab::gui
