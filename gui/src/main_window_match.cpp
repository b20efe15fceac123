// The main window's Match dock (match_dock.h): the database's measurements
// in, an accepted fit out as one undoable edit saved as a new version, with
// the fit recorded against it. Kept apart from main_window.cpp, which calls
// addMatchDock() once.

#include "accuracy_dock.h"
#include "main_window.h"
#include "match_dock.h"
#include "plots_dock.h"
#include "replace_recipe_command.h"

#include "paintlab/database/fit_observations.h"
#include "paintlab/database/measurements.h"

#include <QStatusBar>
#include <QUndoStack>

namespace paintlab::gui {

void MainWindow::addMatchDock() {
    m_match = new MatchDock(&m_document, this);
    addDockWidget(Qt::RightDockWidgetArea, m_match);  // placed by window_layout.h (restoreLayout)
    // The database's measurements are read when the dock is shown (a few
    // small rows; imports elsewhere appear the next time).
    connect(m_match, &QDockWidget::visibilityChanged, this, [this](bool visible) {
        if (visible) refreshMatchMeasurements();
    });
    // The chosen panel overlaid on the a*b* chart and the paint spectra, as
    // the plots' comparison; choosing none removes it (if it is still there).
    connect(m_match, &MatchDock::measuredChanged, this, [this]() {
        if (m_plots == nullptr) return;
        const auto report = m_match->measuredReport();
        if (report) {
            m_plots->setMeasuredComparison(*report, m_match->measuredWavelengths(),
                                           tr("measured: %1").arg(m_match->measuredName()));
        } else if (m_plots->comparisonLabel().startsWith(tr("measured: "))) {
            m_plots->clearComparison();
        }
    });
    connect(m_match, &MatchDock::acceptRequested, this, [this](const Recipe& fitted, const QString& note) {
        m_document.undoStack()->push(new ReplaceRecipeCommand(&m_document, fitted, tr("Accept the fit")));
        if (saveVersionAs(note)) recordMatchFit(note);
    });
}

void MainWindow::refreshMatchMeasurements() {
    if (!m_db) return;
    try {
        std::vector<db::Measurement> measurements;
        for (const auto& summary : db::listMeasurements(*m_db))
            if (auto m = db::findMeasurement(*m_db, summary.name)) measurements.push_back(std::move(*m));
        m_match->setMeasurements(std::move(measurements));
    } catch (const std::exception& e) {
        statusBar()->showMessage(tr("Measurements not read: %1").arg(QString::fromUtf8(e.what())));
    }
}

void MainWindow::recordMatchFit(const QString& note) {
    const fit::FitResult* result = m_match->result();
    const fit::FitProblem* problem = m_match->lastProblem();
    if (!m_db || result == nullptr || problem == nullptr || m_document.version() <= 0) return;
    try {
        // A measurement read from a file is stored with the fit that used it.
        for (const auto& m : m_match->fittedMeasurements())
            if (!db::findMeasurement(*m_db, m.name)) db::createMeasurement(*m_db, m);
        for (const auto& row : db::fitRecords(*result, *problem, m_document.recipe().name,
                                              m_document.version(), note.toStdString()))
            db::recordFit(*m_db, row);
        refreshMatchMeasurements();
    } catch (const std::exception& e) {
        showError(tr("The fit was not recorded"), QString::fromUtf8(e.what()));
    }
}

}  // namespace paintlab::gui
