#pragma once
// Match a sample (issue 28): choose a measurement (from the database or a
// file; optionally a second one through a transparent substrate, from
// below), tick the recipe fields to free with their bounds, run the fit
// (progress, cancel, the best cost as it falls), then read measured against
// fitted: ΔE00 per geometry, each parameter ± 1σ, what the measurement
// cannot tell apart, other recipes that look nearly the same; for a BRDF
// measurement, a sphere shaded half measured, half fitted
// (split_sphere_view.h); and accept
// the fitted recipe as a new version (one undoable step, main window).
//
// The dock holds no database: the main window gives it the measurements and
// takes the accepted fit (acceptRequested). The fit runs on FitRunner's thread.

#include "paintlab/database/measurements.h"
#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/multiangle.h"

#include <QDockWidget>
#include <QString>

#include <memory>
#include <optional>
#include <string>
#include <vector>

class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QSplitter;
class QTableWidget;

namespace paintlab::gui {

class CostCurve;
class FitRunner;
class RecipeDocument;
class SplitSphereView;

class MatchDock : public QDockWidget {
    Q_OBJECT
public:
    explicit MatchDock(RecipeDocument* document, QWidget* parent = nullptr);
    ~MatchDock() override;
    MatchDock(const MatchDock&) = delete;
    MatchDock& operator=(const MatchDock&) = delete;
    MatchDock(MatchDock&&) = delete;
    MatchDock& operator=(MatchDock&&) = delete;

    // The database's measurements (the choice is kept where the name still exists).
    void setMeasurements(std::vector<db::Measurement> measurements);
    // A measurement read from a file (File dialog of the dock, or a test):
    // listed as "name (file)" and chosen.
    void addFileMeasurement(db::Measurement measurement);
    // Reads a measurement file through the plugin registry (the importer of
    // `format_id`, else by extension and content; File... calls it with the
    // dialog's choice) and adds it; false, with the message in the dock, for a bad file.
    bool readFile(const QString& file, const std::optional<std::string>& format_id = {});
    // Ticks a parameter by path with optional bounds (tests, scripts); false if the recipe has no such path.
    bool freeParameter(const QString& path, std::optional<double> lower = {},
                       std::optional<double> upper = {});

    // The fit problem of the dock's current choices; throws InputError naming
    // the field (no measurement, nothing ticked, a bound that is not a number).
    fit::FitProblem problem() const;
    // Runs the fit of problem(); a bad choice shows its message in the dock.
    void run();
    void cancel();
    bool running() const;
    FitRunner* runner() { return m_runner; }

    const fit::FitResult* result() const { return m_result.get(); }
    // The problem of the last fit run (its measurements' names and settings, for the database's record).
    const fit::FitProblem* lastProblem() const { return m_last_problem ? &*m_last_problem : nullptr; }
    // The measurements of the last fit, in the problem's order (top first).
    const std::vector<db::Measurement>& fittedMeasurements() const { return m_fitted_measurements; }

    // What the widgets show (tests).
    QTableWidget* parameterTable() const { return m_parameters; }
    QTableWidget* geometryTable() const { return m_geometries; }
    QTableWidget* resultTable() const { return m_fitted; }
    QLabel* status() const { return m_status; }
    QLabel* warnings() const { return m_warnings; }
    QPushButton* runButton() const { return m_run; }
    QPushButton* cancelButton() const { return m_cancel; }
    QPushButton* acceptButton() const { return m_accept; }
    QComboBox* measurementBox() const { return m_measurement; }
    // The split view of a BRDF measurement against the fitted recipe (or
    // the edited one before a fit); its panes' splitter.
    SplitSphereView* splitView() const { return m_split; }
    QSplitter* panes() const { return m_splitter; }
    // The chosen top measurement (nullptr: none).
    const db::Measurement* chosenMeasurement() const { return chosen(m_measurement); }

    // The chosen top measurement's multi-angle colours as a report (for the
    // plots' measured overlay: its 45° in-plane readings); nullopt for none,
    // a BRDF measurement, or no such reading.
    std::optional<MultiAngleReport> measuredReport() const;
    // Its spectra's wavelengths (empty: CIELAB only) and its name.
    std::vector<double> measuredWavelengths() const;
    QString measuredName() const;

signals:
    // Accept: the fitted recipe, a note for its version, and the result and
    // measurements for the database's fit record.
    void acceptRequested(const paintlab::Recipe& fitted, const QString& note);
    // The chosen measurement changed (nullopt: none or not multi-angle).
    void measuredChanged();

protected:
    void resizeEvent(QResizeEvent* event) override;

private:
    void fillParameters();
    void refreshSplitView();
    void rebuildMeasurementBoxes();
    void showProgress(const fit::FitProgress& progress);
    void showResult(std::shared_ptr<const fit::FitResult> result);
    void showMessage(const QString& text, bool error);
    void setRunning(bool running);
    void importFile();
    const db::Measurement* chosen(const QComboBox* box) const;

    RecipeDocument* m_document;
    FitRunner* m_runner = nullptr;
    std::vector<db::Measurement> m_measurements;  // database ones, then files
    std::vector<bool> m_from_file;
    std::vector<db::Measurement> m_fitted_measurements;
    std::shared_ptr<const fit::FitResult> m_result;
    std::optional<fit::FitProblem> m_last_problem;

    QComboBox* m_measurement = nullptr;
    QComboBox* m_bottom = nullptr;
    QTableWidget* m_parameters = nullptr;
    QSpinBox* m_starts = nullptr;
    QPushButton* m_run = nullptr;
    QPushButton* m_cancel = nullptr;
    QProgressBar* m_progress = nullptr;
    CostCurve* m_curve = nullptr;
    QLabel* m_status = nullptr;
    QLabel* m_warnings = nullptr;
    QTableWidget* m_fitted = nullptr;
    QTableWidget* m_geometries = nullptr;
    QLabel* m_alternatives = nullptr;
    QPushButton* m_accept = nullptr;
    QSplitter* m_splitter = nullptr;
    SplitSphereView* m_split = nullptr;
};

}  // namespace paintlab::gui
