// The main window's Plots dock (gui/plots/plots_dock.h) and its wiring, apart
// from main_window.cpp: it follows the same scheduler result as the central
// in-plane plot (every delivered BRDF), and the edited recipe for the
// ingredients' spectra. A version compared in the render dock is overlaid
// on the plots too, under the same label, until that comparison ends, unless
// the plots show a comparison of their own (a pin, the full model).

#include "main_window.h"
#include "plots_dock.h"
#include "render_dock.h"

namespace paintlab::gui {

void MainWindow::addPlotsDock() {
    m_plots = new PlotsDock(this);  // placed by window_layout.h
    connect(&m_scheduler, &RenderScheduler::finished, m_plots, [this](const RenderResult& result) {
        if (result.brdf) m_plots->setBrdf(result.brdf);
    });
    const auto recipe = [this]() {
        if (m_document.hasRecipe()) m_plots->setRecipe(m_document.recipe());
    };
    connect(&m_document, &RecipeDocument::recipeChanged, m_plots, recipe);
    connect(&m_compare_scheduler, &RenderScheduler::finished, m_plots, [this](const RenderResult& result) {
        if (!result.brdf || !m_render->hasComparison() || m_plots->fullModelRunning()) return;
        const QString& shown = m_plots->comparisonLabel();
        if (!shown.isEmpty() && shown != m_plots_comparison_label) return;  // the user's own
        m_plots_comparison_label = m_render->comparisonLabel();
        m_plots->setComparison(result.brdf, m_plots_comparison_label);
    });
}

void MainWindow::clearPlotsComparisonFromRender() {
    const bool ours =
        !m_plots_comparison_label.isEmpty() && m_plots->comparisonLabel() == m_plots_comparison_label;
    m_plots_comparison_label.clear();
    if (ours && !m_plots->fullModelRunning()) m_plots->clearComparison();
}

}  // namespace paintlab::gui
