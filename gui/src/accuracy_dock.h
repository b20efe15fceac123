#pragma once
// What accuracy costs in time, made visible: the preset policy, the measured
// time of the last recompute and the colour error each preset is known to
// accept (measured against the converged reference preset on the demo
// paints, docs/PERFORMANCE.md).

#include "render_scheduler.h"

#include <QDockWidget>

class QComboBox;
class QLabel;

namespace paintlab::gui {

class AccuracyDock : public QDockWidget {
    Q_OBJECT
public:
    explicit AccuracyDock(QWidget* parent = nullptr);

    // The preset for an edit: automatic = preview while a slider is dragged,
    // standard otherwise; or the one chosen.
    Preset presetFor(bool interactive) const;
    void showResult(const RenderResult& result);

signals:
    void policyChanged();

private:
    QComboBox* m_policy = nullptr;
    QLabel* m_last = nullptr;
};

}  // namespace paintlab::gui
