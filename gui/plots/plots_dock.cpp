#include "plots_dock.h"

#include "ab_chart.h"
#include "inplane_plot.h"
#include "lobe_plot.h"
#include "plot_data.h"
#include "spectra_plot.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QTabWidget>
#include <QTime>
#include <QVBoxLayout>

#include <algorithm>
#include <initializer_list>
#include <utility>

namespace paintlab::gui {

namespace {

// Everything the plots of one BRDF show, computed on the worker.
struct PlotsData {
    std::vector<InplaneCurve> inplane;
    LobeGrid lobe;
    MultiAngleReport report;
    std::vector<NamedSpectrum> spectra;
    double seconds = 0.0;
};

PlotsData computePlotsData(const LayeredBrdf& brdf, double theta_i_deg, double phi_i_deg) {
    QElapsedTimer timer;
    timer.start();
    PlotsData d;
    d.inplane = inplaneCurves(brdf, PlotsDock::inplaneIncidencesDeg());
    d.lobe = lobeGrid(brdf, theta_i_deg, phi_i_deg);
    d.report = multiAngleColours(brdf);
    d.spectra = multiAngleSpectra(d.report, brdf.wavelengthsNm());
    d.seconds = static_cast<double>(timer.nsecsElapsed()) * 1e-9;
    return d;
}

}  // namespace

const std::vector<double>& PlotsDock::inplaneIncidencesDeg() {
    static const std::vector<double> incidences{15.0, 30.0, 45.0, 60.0, 75.0};
    return incidences;
}

PlotsDock::PlotsDock(QWidget* parent) : QDockWidget(tr("Plots"), parent) {
    setObjectName("plots");
    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(4, 4, 4, 4);

    auto* bar = new QHBoxLayout;
    auto* png = new QPushButton(tr("Export PNG..."), body);
    png->setObjectName("plots_export_png");
    auto* csv = new QPushButton(tr("Export CSV..."), body);
    csv->setObjectName("plots_export_csv");
    auto* pin = new QPushButton(tr("Pin for comparison"), body);
    pin->setObjectName("plots_pin");
    pin->setToolTip(tr("Overlay the current BRDF, dashed, on the in-plane, paint spectra and a*b* plots"));
    auto* unpin = new QPushButton(tr("Clear comparison"), body);
    unpin->setObjectName("plots_unpin");
    m_log = new QCheckBox(tr("Log scale"), body);
    m_log->setObjectName("plots_log");
    m_log->setToolTip(tr("Logarithmic axis of the in-plane plot and the paint spectra, and lobe radius "
                         "(values <= 0 are then not drawn)"));
    m_status = new QLabel(body);
    m_status->setObjectName("plots_status");
    // Its text (times, the full model's label) must not widen the dock past
    // the screen: it takes the room left and is cut there.
    m_status->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_status->setMinimumWidth(0);
    m_status->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
    m_full = new QPushButton(tr("Compare with full model"), body);
    m_full->setObjectName("plots_full_model");
    m_full->setToolTip(tr("Run the Monte Carlo full model (explicit flakes, preview grid) for the recipe "
                          "on a worker and overlay it as the comparison"));
    m_full_seconds = new QSpinBox(body);
    m_full_seconds->setObjectName("plots_full_model_seconds");
    m_full_seconds->setRange(1, 600);
    m_full_seconds->setValue(20);
    m_full_seconds->setSuffix(QStringLiteral(" s"));
    m_full_seconds->setToolTip(tr("Time budget of the full model"));
    m_full_progress = new QProgressBar(body);
    m_full_progress->setObjectName("plots_full_model_progress");
    m_full_progress->setRange(0, 100);
    m_full_progress->setMaximumWidth(120);
    m_full_progress->hide();
    m_full_cancel = new QPushButton(tr("Cancel"), body);
    m_full_cancel->setObjectName("plots_full_model_cancel");
    m_full_cancel->hide();
    // Two rows, so the dock fits beside the recipe editor on a 1024-pixel
    // screen: files and comparison first, the full model and the status below.
    for (QWidget* w : std::initializer_list<QWidget*>{png, csv, pin, unpin, m_log}) bar->addWidget(w);
    bar->addStretch(1);
    layout->addLayout(bar);
    auto* full_row = new QHBoxLayout;
    for (QWidget* w : std::initializer_list<QWidget*>{m_full, m_full_seconds, m_full_progress, m_full_cancel})
        full_row->addWidget(w);
    full_row->addWidget(m_status, 1);  // the room left, text at its right end
    layout->addLayout(full_row);

    m_tabs = new QTabWidget(body);
    m_tabs->setObjectName("plots_tabs");
    layout->addWidget(m_tabs, 1);

    // BRDF lobe, with its incidence chooser.
    auto* lobe_page = new QWidget(m_tabs);
    auto* lobe_layout = new QVBoxLayout(lobe_page);
    lobe_layout->setContentsMargins(0, 0, 0, 0);
    auto* chooser = new QHBoxLayout;
    m_theta_i = new QDoubleSpinBox(lobe_page);
    m_theta_i->setObjectName("lobe_theta_i");
    m_theta_i->setRange(0.0, 85.0);
    m_theta_i->setSingleStep(5.0);
    m_theta_i->setDecimals(1);
    m_theta_i->setSuffix(QStringLiteral(" deg"));
    m_theta_i->setValue(45.0);
    m_phi_i = new QDoubleSpinBox(lobe_page);
    m_phi_i->setObjectName("lobe_phi_i");
    m_phi_i->setRange(0.0, 360.0);
    m_phi_i->setWrapping(true);
    m_phi_i->setSingleStep(15.0);
    m_phi_i->setDecimals(1);
    m_phi_i->setSuffix(QStringLiteral(" deg"));
    chooser->addWidget(new QLabel(tr("Light: theta"), lobe_page));
    chooser->addWidget(m_theta_i);
    chooser->addWidget(new QLabel(tr("phi"), lobe_page));
    chooser->addWidget(m_phi_i);
    chooser->addWidget(new QLabel(tr("(drag to rotate, wheel to zoom, double-click to reset)"), lobe_page));
    chooser->addStretch(1);
    lobe_layout->addLayout(chooser);
    m_lobe = new LobePlot(lobe_page);
    m_lobe->setObjectName("lobe_plot");
    lobe_layout->addWidget(m_lobe, 1);
    m_tabs->addTab(lobe_page, tr("BRDF lobe"));
    m_pages.emplace_back(lobe_page, m_lobe);

    m_inplane = new InplanePlot(m_tabs);
    m_inplane->setObjectName("inplane_plot");
    m_inplane->setIncidences(inplaneIncidencesDeg());
    m_tabs->addTab(m_inplane, tr("In-plane"));
    m_pages.emplace_back(m_inplane, m_inplane);

    m_paint_spectra = new SpectraPlot(m_tabs);
    m_paint_spectra->setObjectName("paint_spectra_plot");
    m_tabs->addTab(m_paint_spectra, tr("Paint spectra"));
    m_pages.emplace_back(m_paint_spectra, m_paint_spectra);

    auto* ingredients_page = new QWidget(m_tabs);
    auto* ingredients_layout = new QVBoxLayout(ingredients_page);
    ingredients_layout->setContentsMargins(0, 0, 0, 0);
    auto* quantity_row = new QHBoxLayout;
    m_quantity = new QComboBox(ingredients_page);
    m_quantity->setObjectName("ingredient_quantity");
    quantity_row->addWidget(new QLabel(tr("Quantity"), ingredients_page));
    quantity_row->addWidget(m_quantity, 1);
    ingredients_layout->addLayout(quantity_row);
    m_ingredient_spectra = new SpectraPlot(ingredients_page);
    m_ingredient_spectra->setObjectName("ingredient_spectra_plot");
    ingredients_layout->addWidget(m_ingredient_spectra, 1);
    m_tabs->addTab(ingredients_page, tr("Ingredient spectra"));
    m_pages.emplace_back(ingredients_page, m_ingredient_spectra);

    m_ab = new AbChart(m_tabs);
    m_ab->setObjectName("ab_chart");
    m_tabs->addTab(m_ab, tr("a*b*"));
    m_pages.emplace_back(m_ab, m_ab);

    setWidget(body);

    connect(m_theta_i, &QDoubleSpinBox::valueChanged, this, &PlotsDock::requestUpdate);
    connect(m_phi_i, &QDoubleSpinBox::valueChanged, this, &PlotsDock::requestUpdate);
    for (LatestJob* job : {&m_current_job, &m_comparison_job})
        connect(job, &LatestJob::failed, this, [this](const QString& message) {
            showError(tr("Cannot compute the plots: %1").arg(message));
        });
    connect(m_log, &QCheckBox::toggled, this, [this](bool on) {
        m_inplane->setLogScale(on);
        m_paint_spectra->setLogScale(on);
        m_lobe->setLogRadius(on);
    });
    connect(m_quantity, &QComboBox::currentTextChanged, this, [this](const QString& quantity) {
        if (!quantity.isEmpty()) m_ingredient_spectra->setQuantity(quantity.toStdString());
    });
    connect(m_ingredient_spectra, &SpectraPlot::quantitiesChanged, this, &PlotsDock::fillQuantities);
    connect(pin, &QPushButton::clicked, this, &PlotsDock::pinCurrentAsComparison);
    connect(m_full, &QPushButton::clicked, this, &PlotsDock::compareWithFullModel);
    connect(m_full_cancel, &QPushButton::clicked, this, &PlotsDock::cancelFullModel);
    connect(&m_full_job, &FullModelJob::progress, m_full_progress, &QProgressBar::setValue);
    connect(&m_full_job, &FullModelJob::finished, this, &PlotsDock::fullModelFinished);
    connect(&m_full_job, &FullModelJob::cancelled, this, [this]() {
        showFullModelIdle();
        m_status->setText(tr("full model cancelled"));
        emit fullModelEnded(false);
    });
    connect(&m_full_job, &FullModelJob::failed, this, [this](const QString& message) {
        showFullModelIdle();
        m_status->setText(tr("full model failed"));
        showError(tr("The full model cannot run: %1").arg(message));
        emit fullModelEnded(false);
    });
    connect(unpin, &QPushButton::clicked, this, &PlotsDock::clearComparison);
    connect(png, &QPushButton::clicked, this, [this]() {
        const QString path =
            QFileDialog::getSaveFileName(this, tr("Export plot image"), {}, tr("PNG (*.png)"));
        if (!path.isEmpty()) exportCurrentPng(path);
    });
    connect(csv, &QPushButton::clicked, this, [this]() {
        const QString path =
            QFileDialog::getSaveFileName(this, tr("Export plot data"), {}, tr("CSV (*.csv)"));
        if (!path.isEmpty()) exportCurrentCsv(path);
    });
}

std::vector<PlotWidget*> PlotsDock::plots() const {
    std::vector<PlotWidget*> out;
    for (const auto& [page, plot] : m_pages) out.push_back(plot);
    return out;
}

PlotWidget* PlotsDock::currentPlot() const {
    for (const auto& [page, plot] : m_pages)
        if (page == m_tabs->currentWidget()) return plot;
    return nullptr;
}

PlotsDock::~PlotsDock() = default;

void PlotsDock::setBrdf(std::shared_ptr<const LayeredBrdf> brdf) {
    if (!brdf) return;
    m_brdf = std::move(brdf);
    requestUpdate();
}

void PlotsDock::requestUpdate() {
    if (!m_brdf) return;
    m_current_job.run([this, brdf = m_brdf, theta = m_theta_i->value(), phi = m_phi_i->value()]() {
        auto result = std::make_shared<PlotsData>(computePlotsData(*brdf, theta, phi));
        return LatestJob::Apply([this, result]() {
            QElapsedTimer timer;
            timer.start();
            m_lobe->setGrid(std::move(result->lobe));
            m_inplane->setCurves(std::move(result->inplane));
            m_paint_spectra->setSpectra(std::move(result->spectra),
                                        tr("Paint reflectance factor at the multi-angle geometries"));
            m_ab->setReport(std::move(result->report));
            m_update_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
            m_compute_ms = result->seconds * 1e3;
            // Short enough for the row's room at 1024 px; the tooltip says what the figures are.
            m_status->setText(
                tr("data %1 ms, plots %2 ms").arg(m_compute_ms, 0, 'f', 1).arg(m_update_ms, 0, 'f', 1));
            m_status->setToolTip(tr("The plots' data took %1 ms on a worker thread and %2 ms to hand to the "
                                    "plots, which draw on their own render thread")
                                     .arg(m_compute_ms, 0, 'f', 1)
                                     .arg(m_update_ms, 0, 'f', 1));
            emit updated();
        });
    });
}

void PlotsDock::setRecipe(const Recipe& recipe) {
    m_recipe = std::make_unique<Recipe>(recipe);
    std::vector<NamedSpectrum> spectra = recipeSpectra(recipe);
    if (spectra == m_ingredient_spectra->spectra()) return;
    m_ingredient_spectra->setSpectra(
        std::move(spectra),
        tr("Optical data of the ingredients of %1").arg(QString::fromStdString(recipe.name)));
}

void PlotsDock::fillQuantities() {
    const QSignalBlocker block(m_quantity);
    m_quantity->clear();
    for (const std::string& q : m_ingredient_spectra->quantities())
        m_quantity->addItem(QString::fromStdString(q));
    m_quantity->setCurrentText(QString::fromStdString(m_ingredient_spectra->quantity()));
}

void PlotsDock::setComparison(std::shared_ptr<const LayeredBrdf> brdf, const QString& label) {
    cancelFullModel();  // the newest comparison wins
    setComparisonKeepingFullModel(std::move(brdf), label);
}

void PlotsDock::setComparisonKeepingFullModel(std::shared_ptr<const LayeredBrdf> brdf, const QString& label) {
    if (!brdf) {
        clearComparison();
        return;
    }
    m_comparison = std::move(brdf);
    m_comparison_label = label;
    const quint64 generation = ++m_comparison_generation;
    m_comparison_job.run([this, brdf = m_comparison, label, generation]() {
        auto curves =
            std::make_shared<std::vector<InplaneCurve>>(inplaneCurves(*brdf, inplaneIncidencesDeg()));
        auto report = std::make_shared<MultiAngleReport>(multiAngleColours(*brdf));
        auto spectra =
            std::make_shared<std::vector<NamedSpectrum>>(multiAngleSpectra(*report, brdf->wavelengthsNm()));
        return LatestJob::Apply([this, curves, report, spectra, label, generation]() {
            if (generation != m_comparison_generation) return;  // cleared or replaced meanwhile
            m_inplane->setComparisonCurves(std::move(*curves), label);
            m_paint_spectra->setComparisonSpectra(std::move(*spectra), label);
            m_ab->setComparisonReport(std::move(*report), label);
        });
    });
}

void PlotsDock::setMeasuredComparison(MultiAngleReport report, std::vector<double> wavelengths_nm,
                                      const QString& label) {
    cancelFullModel();
    clearComparison();
    m_comparison_label = label;
    if (!wavelengths_nm.empty())
        m_paint_spectra->setComparisonSpectra(multiAngleSpectra(report, wavelengths_nm), label);
    m_ab->setComparisonReport(std::move(report), label);
}

void PlotsDock::pinCurrentAsComparison() {
    if (m_brdf)
        setComparison(m_brdf, tr("pinned %1").arg(QTime::currentTime().toString(QStringLiteral("HH:mm:ss"))));
}

void PlotsDock::clearComparison() {
    cancelFullModel();
    ++m_comparison_generation;
    m_comparison.reset();
    m_comparison_label.clear();
    m_inplane->clearComparison();
    m_paint_spectra->clearComparison();
    m_ab->clearComparison();
    // The status named the comparison (the full model's run or result): it is gone.
    if (!m_full_label.isEmpty() || m_status->text().startsWith(tr("full model"))) {
        m_status->clear();
        m_status->setToolTip({});
    }
    m_full_label.clear();
}

void PlotsDock::compareWithFullModel() {
    if (!m_recipe) {
        m_status->setText(tr("full model: no recipe"));
        return;
    }
    m_full_recipe = std::make_unique<Recipe>(*m_recipe);
    m_full_started = QTime::currentTime().toString(QStringLiteral("HH:mm:ss"));
    m_full_job.start(*m_full_recipe, m_full_seconds->value());
    m_full_progress->setValue(0);
    m_full_progress->show();
    m_full_cancel->show();
    m_status->setText(tr("full model running (%1 s budget)").arg(m_full_seconds->value()));
}

void PlotsDock::cancelFullModel() {
    if (m_full_job.busy()) m_full_job.cancel();
}

void PlotsDock::showFullModelIdle() {
    m_full_progress->hide();
    m_full_cancel->hide();
}

void PlotsDock::fullModelFinished(const FullModelJob::Result& result) {
    showFullModelIdle();
    QString label =
        tr("full model (Monte Carlo, %1 paths, %2 s)").arg(result.paths).arg(result.seconds, 0, 'f', 1);
    if (m_recipe && m_full_recipe && !(*m_recipe == *m_full_recipe))
        label += tr(" of the recipe as at %1").arg(m_full_started);
    m_full_label = label;
    m_status->setText(label);
    m_status->setToolTip(label);
    setComparisonKeepingFullModel(result.brdf, label);
    emit fullModelEnded(true);
}

bool PlotsDock::exportCurrentPng(const QString& path) {
    PlotWidget* plot = currentPlot();
    if (plot != nullptr && plot->exportPng(path)) return true;
    showError(tr("%1: the plot image cannot be written").arg(path));
    return false;
}

bool PlotsDock::exportCurrentCsv(const QString& path) {
    PlotWidget* plot = currentPlot();
    if (plot != nullptr && plot->exportCsv(path)) return true;
    showError(tr("%1: the plot data cannot be written").arg(path));
    return false;
}

void PlotsDock::showError(const QString& message) {
    auto* box = new QMessageBox(QMessageBox::Warning, tr("Plots"), message, QMessageBox::Ok, this);
    box->setObjectName("error_dialog");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();  // not exec(): the GUI thread never blocks on a dialog's own event loop
}

}  // namespace paintlab::gui
