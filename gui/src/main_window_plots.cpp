// The main window's Plots dock (gui/plots/plots_dock.h) and its wiring, apart
// from main_window.cpp: it follows the same scheduler result as the central
// in-plane plot (every delivered BRDF), and the edited recipe for the
// ingredients' spectra.

#include "main_window.h"
#include "plots_dock.h"

namespace paintlab::gui {

void MainWindow::addPlotsDock() {
    m_plots = new PlotsDock(this);
    addDockWidget(Qt::BottomDockWidgetArea, m_plots);
    connect(&m_scheduler, &RenderScheduler::finished, m_plots, [this](const RenderResult& result) {
        if (result.brdf) m_plots->setBrdf(result.brdf);
    });
    const auto recipe = [this]() {
        if (m_document.hasRecipe()) m_plots->setRecipe(m_document.recipe());
    };
    connect(&m_document, &RecipeDocument::recipeChanged, m_plots, recipe);
}

}  // namespace paintlab::gui
