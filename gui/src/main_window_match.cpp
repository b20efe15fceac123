// The main window's Match dock (match_dock.h): the database's measurements
// in, an accepted fit out as one undoable edit saved as a new version, with
// the fit recorded against it. Kept apart from main_window.cpp, which calls
// addMatchDock() once.

#include "accuracy_dock.h"
#include "inplane_plot.h"
#include "main_window.h"
#include "match_dock.h"
#include "plot_data.h"
#include "plots_dock.h"
#include "replace_recipe_command.h"
#include "split_sphere.h"
#include "split_sphere_view.h"

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
    // A BRDF measurement: its samples in the 45° plane as points on both
    // in-plane plots instead.
    connect(m_match, &MatchDock::measuredChanged, this, [this]() {
        if (m_plots == nullptr) return;
        const auto report = m_match->measuredReport();
        if (report) {
            m_plots->setMeasuredComparison(*report, m_match->measuredWavelengths(),
                                           tr("measured: %1").arg(m_match->measuredName()));
        } else if (m_plots->comparisonLabel().startsWith(tr("measured: ")) ||
                   m_plots->comparisonLabel().startsWith(tr("fitted: "))) {
            m_plots->clearComparison();
            m_plot->clearComparison();
        }
        showMeasuredSamples();
    });
    // The fitted recipe's curves beside a BRDF measurement's points, dashed.
    connect(m_match->splitView(), &SplitSphereView::recipeBrdfReady, this,
            [this](std::shared_ptr<const LayeredBrdf> brdf, const QString& right_label) {
                if (m_plots == nullptr || right_label != tr("fitted")) return;
                const QString label = tr("fitted: %1").arg(m_match->measuredName());
                m_plot->setComparison(*brdf, label);
                m_plots->setComparison(std::move(brdf), label);
            });
    connect(m_match, &MatchDock::acceptRequested, this, [this](const Recipe& fitted, const QString& note) {
        m_document.undoStack()->push(new ReplaceRecipeCommand(&m_document, fitted, tr("Accept the fit")));
        if (saveVersionAs(note)) recordMatchFit(note);
    });
}

void MainWindow::showMeasuredSamples() {
    const db::Measurement* m = m_match->chosenMeasurement();
    InplanePlot* plots_inplane = m_plots->inplanePlot();
    if (m == nullptr || m->kind != db::MeasurementKind::Brdf) {
        if (plots_inplane->hasMeasuredSamples()) plots_inplane->clearMeasuredSamples();
        if (m_plot->hasMeasuredSamples()) m_plot->clearMeasuredSamples();
        return;
    }
    // A few thousand samples: milliseconds, on the GUI thread.
    try {
        const auto samples = linearSrgbSamples(*m);
        const QString name = QString::fromStdString(m->name);
        InplaneSamples points = inplaneSamples(samples, 45.0);
        plots_inplane->setMeasuredSamples(points, name);
        m_plot->setMeasuredSamples(std::move(points), name);
    } catch (const std::exception& e) {
        statusBar()->showMessage(tr("Measured samples not shown: %1").arg(QString::fromUtf8(e.what())));
    }
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
