// The render dock's comparison in the main window (kept out of
// main_window.cpp): a second scheduler renders the comparison recipe (a
// version picked in the Versions dock, or the edited recipe pinned) with the
// edited recipe's ray map, exposure, preset and plan setting, so the two
// sides differ by the recipe alone. Each side's newest request wins on its
// own scheduler; neither waits for the other, and the GUI thread for neither.

#include "main_window.h"

#include "accuracy_dock.h"
#include "render_dock.h"
#include "versions_dock.h"

#include <QTime>
#include <QUndoStack>

namespace paintlab::gui {

void MainWindow::connectComparison() {
    connect(&m_compare_scheduler, &RenderScheduler::finished, m_render, &RenderDock::showComparison);
    connect(&m_compare_scheduler, &RenderScheduler::failed, this,
            [this](quint64 /*generation*/, const QString& message) {
                showError(tr("Rendering the comparison failed"), message);
            });
    connect(m_versions, &VersionsDock::comparisonRequested, this, &MainWindow::compareWith);
    connect(m_render, &RenderDock::pinCurrentRequested, this, [this]() {
        if (m_document.hasRecipe())
            compareWith(m_document.recipe(),
                        tr("%1 (pinned %2)").arg(currentLabel(), QTime::currentTime().toString("HH:mm:ss")));
    });
    connect(m_render, &RenderDock::clearComparisonRequested, this, &MainWindow::clearComparison);
    // The label of the edited side follows what is edited.
    const auto relabel = [this]() {
        m_render->setCurrentLabel(currentLabel());
        updateTitle();
    };
    connect(&m_document, &RecipeDocument::recipeLoaded, this, relabel);
    connect(m_document.undoStack(), &QUndoStack::cleanChanged, this, relabel);
    connect(this, &MainWindow::versionSaved, this, relabel);
}

QString MainWindow::currentLabel() {
    if (!m_document.hasRecipe()) return {};
    if (!m_document.hasUnsavedEdits()) return m_document.origin();
    // Undone past a save, or edited since: not what that version holds.
    if (m_document.version() > 0)
        return tr("%1, modified since version %2")
            .arg(QString::fromStdString(m_document.recipe().name))
            .arg(m_document.version());
    return tr("%1, edited").arg(m_document.origin());
}

void MainWindow::updateTitle() {
    setWindowTitle(m_document.hasRecipe() ? tr("PaintLab - %1").arg(currentLabel()) : tr("PaintLab"));
}

void MainWindow::compareWith(const Recipe& recipe, const QString& label) {
    m_comparison = recipe;
    m_render->setCurrentLabel(currentLabel());
    m_render->setComparisonLabel(label);
    requestComparison(true);
}

void MainWindow::clearComparison() {
    m_comparison.reset();
    m_comparison_key.reset();
    // A request of nothing is not possible: a newer generation cancels what runs.
    m_render->clearComparison();
    clearPlotsComparisonFromRender();
}

void MainWindow::requestComparison(bool always) {
    if (!m_comparison) return;
    const ComparisonKey key{m_last_preset, m_accuracy->followPlan(), m_scheduler.exposure(),
                            m_scheduler.rayMap().get()};
    if (!always && m_comparison_key == key) return;  // the comparison's image is still right
    m_comparison_key = key;
    m_compare_scheduler.setFollowPlan(key.follow_plan);
    m_compare_scheduler.setExposure(key.exposure_ev);
    m_compare_scheduler.shareRayMap(m_scheduler);
    m_compare_scheduler.request(*m_comparison, key.preset);
}

}  // namespace paintlab::gui
