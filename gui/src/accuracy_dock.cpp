#include "accuracy_dock.h"

#include <QComboBox>
#include <QLabel>
#include <QVBoxLayout>

namespace paintlab::gui {

AccuracyDock::AccuracyDock(QWidget* parent) : QDockWidget(tr("Accuracy"), parent) {
    setObjectName("accuracy");
    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);
    m_policy = new QComboBox(body);
    m_policy->setObjectName("preset_policy");
    m_policy->addItem(tr("Automatic: preview while dragging, standard when released"));
    m_policy->addItem(tr("Always preview"));
    m_policy->addItem(tr("Always standard"));
    m_policy->addItem(tr("Always reference (seconds per edit)"));
    layout->addWidget(m_policy);
    // Worst CIEDE2000 over the six multi-angle geometries against the reference
    // preset, measured on the five demo paints (presetSettings, docs/PERFORMANCE.md).
    auto* expected = new QLabel(
        tr("Expected colour error (worst CIEDE2000 of the demo paints "
           "at the six multi-angle geometries, against the reference):\n"
           "  preview   \u2264 0.6\n  standard  \u2264 0.08\n  reference converged (< 1e-4 in reflectance)"),
        body);
    layout->addWidget(expected);
    m_last = new QLabel(tr("No recompute yet"), body);
    m_last->setObjectName("last_recompute");
    layout->addWidget(m_last);
    layout->addStretch(1);
    setWidget(body);
    connect(m_policy, &QComboBox::currentIndexChanged, this, &AccuracyDock::policyChanged);
}

Preset AccuracyDock::presetFor(bool interactive) const {
    switch (m_policy->currentIndex()) {
    case 1:
        return Preset::Preview;
    case 2:
        return Preset::Standard;
    case 3:
        return Preset::Reference;
    default:
        return interactive ? Preset::Preview : Preset::Standard;
    }
}

void AccuracyDock::showResult(const RenderResult& result) {
    const double total = result.brdf_ms + result.tables_ms + result.relight_ms;
    m_last->setText(tr("Last recompute (%1): %2 ms in all\n  fast model %3 ms (%4 bands computed)\n"
                       "  relight tables %5 ms\n  relight %6 ms")
                        .arg(QString::fromUtf8(presetName(result.preset).data()))
                        .arg(total, 0, 'f', 1)
                        .arg(result.brdf_ms, 0, 'f', 1)
                        .arg(result.brdf ? result.brdf->settings().bands : 0)
                        .arg(result.tables_ms, 0, 'f', 1)
                        .arg(result.relight_ms, 0, 'f', 1));
}

}  // namespace paintlab::gui
