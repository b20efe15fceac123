#include "accuracy_dock.h"

#include "paintlab/engine/plan/plan.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

namespace paintlab::gui {

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

// A word-wrapped label's minimum width follows its text (QLabel picks a
// width for a pleasant line count): with the measured times in it, the dock
// and the window's layout would change from one recompute to the next. The
// dock's width is the user's; the label wraps to it.
void keepWidthFree(QLabel* label) {
    label->setMinimumWidth(120);
    label->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
}

}  // namespace

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
    m_follow_plan = new QCheckBox(tr("Follow the effect plan"), body);
    m_follow_plan->setObjectName("follow_plan");
    m_follow_plan->setChecked(true);
    m_follow_plan->setToolTip(tr("On: the fast model at the plan's orders, bands and slices, sparkle where "
                                 "the plan finds glints visible. Off: the preset as it is, no sparkle."));
    layout->addWidget(m_follow_plan);
    m_plan_summary = new QLabel(tr("No plan yet"), body);
    m_plan_summary->setObjectName("plan_summary");
    m_plan_summary->setWordWrap(true);
    keepWidthFree(m_plan_summary);
    layout->addWidget(m_plan_summary);
    m_plan_table = new QTableWidget(0, 4, body);
    m_plan_table->setObjectName("plan_decisions");
    m_plan_table->setHorizontalHeaderLabels(
        {tr("Effect"), tr("Runs"), tr("Accepted \u0394E00"), tr("Reason")});
    m_plan_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_plan_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_plan_table->verticalHeader()->hide();
    m_plan_table->horizontalHeader()->setStretchLastSection(true);
    m_plan_table->setWordWrap(false);
    layout->addWidget(m_plan_table, 1);
    // Worst CIEDE2000 over the six multi-angle geometries against the reference
    // preset, measured on the five demo paints (presetSettings, docs/PERFORMANCE.md).
    auto* expected =
        new QLabel(tr("The presets' expected colour error (worst CIEDE2000 of the demo paints at "
                      "the six multi-angle geometries, against the reference): preview \u2264 0.6, "
                      "standard \u2264 0.08, reference converged (< 1e-4 in reflectance)."),
                   body);
    expected->setWordWrap(true);
    keepWidthFree(expected);
    layout->addWidget(expected);
    m_last = new QLabel(tr("No recompute yet"), body);
    m_last->setObjectName("last_recompute");
    m_last->setWordWrap(true);
    keepWidthFree(m_last);
    layout->addWidget(m_last);
    setWidget(body);
    connect(m_policy, &QComboBox::currentIndexChanged, this, &AccuracyDock::policyChanged);
    connect(m_follow_plan, &QCheckBox::toggled, this, &AccuracyDock::policyChanged);
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

bool AccuracyDock::followPlan() const { return m_follow_plan->isChecked(); }

void AccuracyDock::setFollowPlan(bool follow) { m_follow_plan->setChecked(follow); }

void AccuracyDock::showResult(const RenderResult& result) {
    showPlan(result);
    const double total =
        result.plan_ms + result.brdf_ms + result.tables_ms + result.relight_ms + result.sparkle_ms;
    const FastModelSettings settings = result.brdf ? result.brdf->settings() : FastModelSettings{};
    m_last->setText(tr("Last recompute (%1%2): %3 ms in all = plan %4 ms + fast model %5 ms (orders %6, %7 "
                       "bands, %8 slices) + relight tables %9 ms + relight %10 ms + sparkle %11")
                        .arg(qs(std::string(presetName(result.preset))),
                             result.follow_plan ? tr(", plan followed") : tr(", plain preset"))
                        .arg(total, 0, 'f', 1)
                        .arg(result.plan_ms, 0, 'f', 1)
                        .arg(result.brdf_ms, 0, 'f', 1)
                        .arg(settings.orders)
                        .arg(settings.bands)
                        .arg(settings.slices)
                        .arg(result.tables_ms, 0, 'f', 1)
                        .arg(result.relight_ms, 0, 'f', 1)
                        .arg(result.sparkle ? tr("%1 ms").arg(result.sparkle_ms, 0, 'f', 1) : tr("off")));
}

void AccuracyDock::showPlan(const RenderResult& result) {
    if (!result.plan) {
        m_plan_table->setRowCount(0);
        m_plan_summary->setText(tr("Effect plan off: the %1 preset's settings as they are, no sparkle.")
                                    .arg(qs(std::string(presetName(result.preset)))));
        return;
    }
    const EffectPlan& plan = *result.plan;
    const bool has_image = !result.image.isNull();
    const std::vector<AppliedDecision> applied = appliedDecisions(plan);
    double accepted_sum = 0.0;
    m_plan_table->setRowCount(static_cast<int>(applied.size()));
    for (int row = 0; row < m_plan_table->rowCount(); ++row) {
        const AppliedDecision& a = applied[static_cast<std::size_t>(row)];
        QString runs = qs(a.applied);
        double accepted = a.accepted_error_de;
        // Glints are drawn into the relit image: with no scene open there is
        // none, so what the plan would draw is skipped and its error accepted.
        if (a.effect == "sparkle" && plan.sparkle && (!has_image || result.sparkle_deferred)) {
            runs = has_image ? tr("on in the plan; left out of the preview (drawn when released)")
                             : tr("on in the plan; not drawn (no image)");
            for (const PlanDecision& d : plan.decisions)
                if (d.effect == "sparkle") accepted = d.skip_error_de;
        }
        accepted_sum += accepted;
        const QStringList cells = {qs(a.effect), runs, QString::number(accepted, 'g', 3), qs(a.reason)};
        for (int col = 0; col < cells.size(); ++col) {
            auto* item = new QTableWidgetItem(cells[col]);
            item->setToolTip(cells[col]);
            m_plan_table->setItem(row, col, item);
        }
    }
    m_plan_table->resizeColumnsToContents();
    m_plan_summary->setText(
        tr("Effect plan for %1, preset %2: tolerance \u0394E00 %3 per pixel (99th percentile); "
           "expected error \u2264 %4 (the decisions' accepted errors added).")
            .arg(result.plan_scene, qs(std::string(presetName(plan.preset))))
            .arg(plan.tolerance_de, 0, 'g', 2)
            .arg(accepted_sum, 0, 'g', 3));
}

}  // namespace paintlab::gui
