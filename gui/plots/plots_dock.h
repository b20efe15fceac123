#pragma once
// The "Plots" dock: one tab per plot of the paint being edited (BRDF lobe,
// in-plane curves, paint spectra, ingredient spectra, a*b* chart), fed with
// every new BRDF the render scheduler delivers and with the recipe itself
// (for its ingredients' spectra). A comparison (a pinned earlier state, or any
// BRDF another panel hands over: a saved version, the full model) is overlaid
// dashed on the in-plane, paint spectra and a*b* plots. Export of the shown plot as PNG and
// of its data as CSV.
//
// The plot data (lobe grid, in-plane curves, multi-angle colours and spectra)
// is computed on a worker thread (latest_job.h, newest request first); the
// GUI thread only hands it to VTK (gui/README.md, "Plots", for the times).
//
// "Compare with full model" runs the Monte Carlo full model (explicit flakes,
// on the preview preset's grid, a time budget from the spin box beside it) on
// its own worker (full_model_job.h) and overlays the result as the
// comparison. The run keeps the recipe it started with: an edit meanwhile
// does not stop it, and the label then says the result is of the recipe as
// it was at the start. Any newer comparison (pin, another run, clear)
// cancels a running one.

#include "full_model_job.h"
#include "latest_job.h"

#include "paintlab/engine/multiangle.h"

#include <QDockWidget>
#include <QString>

#include <memory>
#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;

namespace paintlab {
class LayeredBrdf;
struct Recipe;
}  // namespace paintlab

namespace paintlab::gui {

class AbChart;
class InplanePlot;
class LobePlot;
class PlotWidget;
class SpectraPlot;

class PlotsDock : public QDockWidget {
    Q_OBJECT
public:
    explicit PlotsDock(QWidget* parent = nullptr);
    ~PlotsDock() override;
    PlotsDock(const PlotsDock&) = delete;
    PlotsDock& operator=(const PlotsDock&) = delete;
    PlotsDock(PlotsDock&&) = delete;
    PlotsDock& operator=(PlotsDock&&) = delete;

    // Every plot follows this BRDF: its data is computed on the worker
    // (lastComputeMs()), then drawn (lastUpdateMs() on the GUI thread).
    void setBrdf(std::shared_ptr<const LayeredBrdf> brdf);
    // The ingredients' spectra of this recipe (redrawn only when they change).
    void setRecipe(const Recipe& recipe);
    // Overlaid dashed on the in-plane, paint spectra and a*b* plots until cleared or replaced.
    void setComparison(std::shared_ptr<const LayeredBrdf> brdf, const QString& label);
    // A measured panel as the comparison (Match dock): its a*b* flop path on
    // the a*b* chart and, where it has spectra (at wavelengths_nm), its
    // reflectance factor per geometry on the paint spectra. Replaces any
    // other comparison; cleared like one.
    void setMeasuredComparison(MultiAngleReport report, std::vector<double> wavelengths_nm,
                               const QString& label);
    // The current BRDF becomes the comparison ("pinned").
    void pinCurrentAsComparison();
    void clearComparison();
    // The label of the comparison overlaid (or being computed); empty without one.
    const QString& comparisonLabel() const { return m_comparison_label; }
    // The full model for the last recipe handed to setRecipe (nothing without
    // one), with the spin box's budget; replaces a running one.
    void compareWithFullModel();
    void cancelFullModel();
    bool fullModelRunning() const { return m_full_job.busy(); }
    QSpinBox* fullModelSeconds() const { return m_full_seconds; }
    QLabel* status() const { return m_status; }
    // The label of the last full-model result (also shown in the status until
    // the next plot update); empty again after clearComparison.
    const QString& fullModelLabel() const { return m_full_label; }

    const std::shared_ptr<const LayeredBrdf>& brdf() const { return m_brdf; }
    // GUI-thread time of the last update (VTK only), and the worker's time for its data.
    double lastUpdateMs() const { return m_update_ms; }
    double lastComputeMs() const { return m_compute_ms; }
    // Plot data is being computed or waits to be.
    bool computing() const { return m_current_job.busy() || m_comparison_job.busy(); }
    static const std::vector<double>& inplaneIncidencesDeg();

    InplanePlot* inplanePlot() const { return m_inplane; }
    LobePlot* lobePlot() const { return m_lobe; }
    SpectraPlot* paintSpectra() const { return m_paint_spectra; }
    SpectraPlot* ingredientSpectra() const { return m_ingredient_spectra; }
    AbChart* abChart() const { return m_ab; }
    std::vector<PlotWidget*> plots() const;
    QTabWidget* tabs() const { return m_tabs; }
    // The plot of the shown tab.
    PlotWidget* currentPlot() const;

    // The shown plot as PNG / its data as CSV; false and an error dialog
    // naming the file on failure.
    bool exportCurrentPng(const QString& path);
    bool exportCurrentCsv(const QString& path);

signals:
    // The plots show the data of the newest BRDF handed in (after setBrdf or an incidence change).
    void updated();
    // A full-model run ended: its overlay is on its way (ok) or it failed or was cancelled.
    void fullModelEnded(bool ok);

private:
    void requestUpdate();
    void showError(const QString& message);
    void fillQuantities();
    void setComparisonKeepingFullModel(std::shared_ptr<const LayeredBrdf> brdf, const QString& label);
    void fullModelFinished(const FullModelJob::Result& result);
    void showFullModelIdle();

    QTabWidget* m_tabs = nullptr;
    InplanePlot* m_inplane = nullptr;
    LobePlot* m_lobe = nullptr;
    SpectraPlot* m_paint_spectra = nullptr;
    SpectraPlot* m_ingredient_spectra = nullptr;
    AbChart* m_ab = nullptr;
    QDoubleSpinBox* m_theta_i = nullptr;
    QDoubleSpinBox* m_phi_i = nullptr;
    QComboBox* m_quantity = nullptr;
    QCheckBox* m_log = nullptr;
    QLabel* m_status = nullptr;
    QPushButton* m_full = nullptr;
    QPushButton* m_full_cancel = nullptr;
    QSpinBox* m_full_seconds = nullptr;
    QProgressBar* m_full_progress = nullptr;
    std::unique_ptr<Recipe> m_recipe;       // the last one handed to setRecipe
    std::unique_ptr<Recipe> m_full_recipe;  // the one the running full model was started with
    QString m_full_started;                 // HH:mm:ss of that start
    QString m_full_label;
    std::shared_ptr<const LayeredBrdf> m_brdf;
    std::shared_ptr<const LayeredBrdf> m_comparison;
    std::vector<std::pair<QWidget*, PlotWidget*>> m_pages;  // tab page -> its plot
    double m_update_ms = 0.0;
    double m_compute_ms = 0.0;
    QString m_comparison_label;
    quint64 m_comparison_generation = 0;  // a comparison result of an older one is dropped
    // Members, not children: destroyed (waiting for their work) before the plots are.
    LatestJob m_current_job;
    LatestJob m_comparison_job;
    FullModelJob m_full_job;
};

}  // namespace paintlab::gui
