#include "accuracy_dock.h"

#include "paintlab/engine/model_validity.h"
#include "paintlab/engine/plan/plan.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <exception>
#include <string>
#include <vector>

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

QString de(double value) { return QString::number(value, 'g', value < 10.0 ? 2 : 3); }

// The plan's decisions as the render applied them, with the error each
// accepts: a glint pass left out of the image accepts its skip error.
struct ShownDecision {
    AppliedDecision applied;
    double accepted = 0.0;
};

std::vector<ShownDecision> shownDecisions(const RenderResult& result) {
    const EffectPlan& plan = *result.plan;
    const bool has_image = !result.image.isNull();
    std::vector<ShownDecision> out;
    for (const AppliedDecision& a : appliedDecisions(plan)) {
        ShownDecision d{a, a.accepted_error_de};
        // Glints are drawn into the relit image: with no scene open there is
        // none, so what the plan would draw is skipped and its error accepted.
        if (a.effect == "sparkle" && plan.sparkle && (!has_image || result.sparkle_deferred)) {
            d.applied.applied = has_image ? "on in the plan; left out of the preview (drawn when released)"
                                          : "on in the plan; not drawn (no image)";
            for (const PlanDecision& p : plan.decisions)
                if (p.effect == "sparkle") d.accepted = p.skip_error_de;
        }
        out.push_back(std::move(d));
    }
    return out;
}

// The full model is advised where the fast model's own error (the plan's
// skip error of the full model: the worst of the six multi-angle geometries,
// what the worst pixels see) is above half the preset's tolerance, the
// plan's bar for every effect it skips, whatever its decision on the mean
// difference ("not needed") says: that error is part of the expected error
// the summary adds up, and the verdict must not call it fine.
bool fullModelIsTheCause(const ShownDecision& d, double tolerance_de) {
    return d.applied.effect == "full_model" && d.accepted > 0.5 * tolerance_de;
}

}  // namespace

AccuracyDock::AccuracyDock(QWidget* parent) : QDockWidget(tr("Accuracy"), parent) {
    setObjectName("accuracy");
    auto* scroll = new QScrollArea(this);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    auto* body = new QWidget(scroll);
    auto* layout = new QVBoxLayout(body);
    m_verdict = new QLabel(tr("No recipe open: pick one in the Recipes list to see how far its render "
                              "can be trusted."),
                           body);
    m_verdict->setObjectName("accuracy_verdict");
    m_verdict->setWordWrap(true);
    keepWidthFree(m_verdict);
    layout->addWidget(m_verdict);
    m_run_full = new QPushButton(tr("Compare with the full model"), body);
    m_run_full->setObjectName("accuracy_run_full_model");
    m_run_full->setToolTip(tr("Runs the Monte Carlo full model (explicit flakes) and overlays it on the "
                              "Plots dock's curves"));
    m_run_full->hide();
    layout->addWidget(m_run_full, 0, Qt::AlignLeft);
    auto* details = new QLabel(tr("<b>Details</b>"), body);
    layout->addWidget(details);
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
    auto* expected = new QLabel(
        tr("The fast model's numerical error at each preset (worst CIEDE2000 of the demo paints at the six "
           "multi-angle geometries, against its converged reference preset; the limits of the fast model "
           "itself are the full_model row above): preview \u2264 0.6, standard \u2264 0.08, reference "
           "converged (< 1e-4 in reflectance)."),
        body);
    expected->setWordWrap(true);
    keepWidthFree(expected);
    layout->addWidget(expected);
    m_last = new QLabel(tr("No recompute yet"), body);
    m_last->setObjectName("last_recompute");
    m_last->setWordWrap(true);
    keepWidthFree(m_last);
    layout->addWidget(m_last);
    scroll->setWidget(body);
    setWidget(scroll);
    connect(m_run_full, &QPushButton::clicked, this, &AccuracyDock::fullModelRequested);
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

void AccuracyDock::showNoRecipe() {
    setVerdict(tr("No recipe open: pick one in the Recipes list to see how far its render can be trusted."),
               true, false);
}

void AccuracyDock::setVerdict(const QString& text, bool ok, bool advise_full_model) {
    m_verdict->setText(text);
    m_verdict->setStyleSheet(ok ? QString() : QStringLiteral("QLabel { color: #a33; font-weight: bold; }"));
    m_run_full->setVisible(advise_full_model);
}

void AccuracyDock::showResult(const RenderResult& result, const Recipe* recipe) {
    showPlan(result, recipe);
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

void AccuracyDock::showPlan(const RenderResult& result, const Recipe* recipe) {
    const QString preset = qs(std::string(presetName(result.preset)));
    if (!result.plan) {
        m_plan_table->setRowCount(0);
        m_plan_summary->setText(
            tr("Effect plan off: the %1 preset's settings as they are, no sparkle.").arg(preset));
        setVerdict(tr("No estimate of this render's error with the effect plan off: turn on \"Follow the "
                      "effect plan\" for a verdict."),
                   true, false);
        return;
    }
    const EffectPlan& plan = *result.plan;
    std::vector<ShownDecision> shown = shownDecisions(result);
    double accepted_sum = 0.0;
    const ShownDecision* largest = nullptr;
    for (const ShownDecision& d : shown) {
        accepted_sum += d.accepted;
        if (largest == nullptr || d.accepted > largest->accepted) largest = &d;
    }
    const double tolerance = plan.tolerance_de;
    bool advise_full = false;
    for (const ShownDecision& d : shown) advise_full = advise_full || fullModelIsTheCause(d, tolerance);
    advise_full = advise_full && accepted_sum > tolerance;

    // The verdict, from the same sum the summary below shows.
    if (!(accepted_sum > tolerance)) {
        setVerdict(tr("This render is within \u0394E00 %1 of the converged model (the %2 preset allows %3).")
                       .arg(de(accepted_sum), preset, de(tolerance)),
                   true, false);
    } else if (advise_full) {
        double full_error = 0.0;
        for (const ShownDecision& d : shown)
            if (d.applied.effect == "full_model") full_error = d.accepted;
        QString where;
        try {
            if (recipe != nullptr) {
                const FastModelValidity v = fastModelValidity(*recipe);
                const double percent = 100.0 * v.largest_rel_difference;
                where = tr(" at 45as%1 (%2%3 %)")
                            .arg(v.largest_at_aspecular_deg, 0, 'f', 0)
                            .arg(percent < 0.0 ? QString(QChar(0x2212)) : QStringLiteral("+"))
                            .arg(std::abs(percent), 0, 'f', 0);
            }
        } catch (const std::exception&) {
            where.clear();  // the plan accepted the recipe; nothing to add if this one does not
        }
        setVerdict(tr("The fast model is not valid for this paint%1: the full model is advised. The fast "
                      "model alone may be off by \u0394E00 %2 here; the %3 preset allows %4 (all effects: "
                      "\u2264 %5, below).")
                       .arg(where, de(full_error), preset, de(tolerance), de(accepted_sum)),
                   false, true);
    } else if (largest != nullptr) {
        setVerdict(tr("This render may be off by up to \u0394E00 %1 (the %2 preset allows %3), mostly from "
                      "%4: %5.")
                       .arg(de(accepted_sum), preset, de(tolerance), qs(largest->applied.effect),
                            qs(largest->applied.applied)),
                   false, false);
    }

    // The details, in the plan's order.
    m_plan_table->setRowCount(static_cast<int>(shown.size()));
    for (int row = 0; row < m_plan_table->rowCount(); ++row) {
        const ShownDecision& d = shown[static_cast<std::size_t>(row)];
        QString runs = qs(d.applied.applied);
        if (advise_full && d.applied.effect == "full_model" && !d.applied.changed)
            runs = tr("fast model only; the full model is advised (its error here is above the preset's)");
        const QStringList cells = {qs(d.applied.effect), runs, de(d.accepted), qs(d.applied.reason)};
        for (int col = 0; col < cells.size(); ++col) {
            auto* item = new QTableWidgetItem(cells[col]);
            item->setToolTip(cells[col]);
            m_plan_table->setItem(row, col, item);
        }
    }
    m_plan_table->resizeColumnsToContents();
    // Every decision in sight without scrolling the table (the dock scrolls instead).
    const int rows_height = m_plan_table->verticalHeader()->length();
    m_plan_table->setMinimumHeight(rows_height + m_plan_table->horizontalHeader()->height() +
                                   2 * m_plan_table->frameWidth() +
                                   m_plan_table->horizontalScrollBar()->sizeHint().height());
    m_plan_summary->setText(
        tr("Effect plan for %1, preset %2: tolerance \u0394E00 %3 per pixel (99th percentile); "
           "expected error \u2264 %4 (the decisions' accepted errors added).")
            .arg(result.plan_scene, qs(std::string(presetName(plan.preset))))
            .arg(de(tolerance), de(accepted_sum)));
}

}  // namespace paintlab::gui
