// The Match dock (match_dock.h).

#include "match_dock.h"

#include "cost_curve.h"
#include "fit_runner.h"
#include "format_dialog.h"
#include "recipe_document.h"
#include "split_sphere_view.h"

#include "paintlab/database/exchange.h"
#include "paintlab/database/fit_observations.h"
#include "paintlab/database/measurements.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/plugins/exchange.h"
#include "paintlab/plugins/registry.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <map>

namespace paintlab::gui {

namespace {

constexpr int kColumnParameter = 0;  // checkable: freed or not
constexpr int kColumnNow = 1;
constexpr int kColumnLower = 2;
constexpr int kColumnUpper = 3;
constexpr int kPathRole = Qt::UserRole + 1;

QString number(double value) { return QString::fromStdString(io::formatNumber(value)); }

// A bound as typed: empty = the allowed range's end; C or the user's locale.
std::optional<double> parseBound(const QString& text, const std::string& field) {
    const QString trimmed = text.trimmed();
    if (trimmed.isEmpty()) return std::nullopt;
    bool ok = false;
    double value = trimmed.toDouble(&ok);
    if (!ok) value = QLocale().toDouble(trimmed, &ok);
    if (!ok || !std::isfinite(value))
        throw InputError("Match", field, "'" + trimmed.toStdString() + "' is not a number");
    return value;
}

// Compact rows (a line of text each), smooth vertical scrolling, long texts
// elided in the middle (the tooltips hold them whole).
QTableWidget* makeTable(const QStringList& headers, const char* name) {
    auto* table = new QTableWidget(0, static_cast<int>(headers.size()));
    table->setObjectName(name);
    table->setHorizontalHeaderLabels(headers);
    table->verticalHeader()->hide();
    table->verticalHeader()->setDefaultSectionSize(table->fontMetrics().height() + 8);
    table->setVerticalScrollMode(QAbstractItemView::ScrollPerPixel);
    table->setHorizontalScrollMode(QAbstractItemView::ScrollPerPixel);
    table->setWordWrap(false);
    table->setTextElideMode(Qt::ElideMiddle);
    table->horizontalHeader()->setStretchLastSection(true);
    table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table->setMinimumHeight(80);
    return table;
}

// A pane of the dock's splitter: its widgets stacked, scrolling vertically
// when the pane is shorter than they need.
QWidget* scrollingPane(QWidget* content, const char* name) {
    auto* scroll = new QScrollArea;
    scroll->setObjectName(name);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setWidget(content);
    return scroll;
}

QString geometryName(const fit::GeometryMatch& g) {
    return QString::fromStdString(
               db::multiAngleGeometryName(g.illumination_deg, g.aspecular_deg, g.azimuth_deg)) +
           (g.side == fit::Side::Bottom ? QObject::tr(" (below)") : QString());
}

QString labText(const Lab& lab) {
    return QStringLiteral("%1, %2, %3").arg(lab.L, 0, 'f', 1).arg(lab.a, 0, 'f', 1).arg(lab.b, 0, 'f', 1);
}

}  // namespace

MatchDock::MatchDock(RecipeDocument* document, QWidget* parent)
    : QDockWidget(tr("Match"), parent), m_document(document), m_runner(new FitRunner(this)) {
    setObjectName("match_dock");
    // Three panes in a splitter: the choices (measurement, fields), the run
    // and its results, the split view. Side by side in a wide dock (the bottom tab
    // of a laptop's layout), stacked in a tall one (resizeEvent).
    auto* setup = new QWidget;
    auto* layout = new QVBoxLayout(setup);
    layout->setContentsMargins(4, 4, 4, 4);

    auto* form = new QFormLayout;
    auto* measurement_row = new QHBoxLayout;
    m_measurement = new QComboBox;
    m_measurement->setObjectName("match_measurement");
    m_measurement->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_measurement->setMinimumContentsLength(8);
    m_measurement->setToolTip(tr("The measured panel to match: multi-angle readings or BRDF samples"));
    auto* import = new QPushButton(tr("File..."));
    import->setObjectName("match_import");
    import->setToolTip(
        tr("Read a measurement file (any format db import reads) without storing it; it is stored with "
           "an accepted fit"));
    measurement_row->addWidget(m_measurement, 1);
    measurement_row->addWidget(import);
    form->addRow(tr("Measured"), measurement_row);
    m_bottom = new QComboBox;
    m_bottom->setObjectName("match_bottom_measurement");
    m_bottom->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_bottom->setMinimumContentsLength(12);
    m_bottom->setToolTip(tr("The same coating measured from below through its transparent substrate "
                            "(fitted jointly: separates a concentration gradient)"));
    form->addRow(tr("From below"), m_bottom);
    layout->addLayout(form);

    m_parameters =
        makeTable({tr("Field (tick to fit)"), tr("Now"), tr("Lower"), tr("Upper")}, "match_parameters");
    m_parameters->setToolTip(
        tr("Tick the recipe fields the fit may change; bounds default to the allowed range"));
    // The field names take the room left; Now, Lower and Upper keep a
    // number's width (typed bounds must stay readable).
    m_parameters->horizontalHeader()->setStretchLastSection(false);
    m_parameters->horizontalHeader()->setSectionResizeMode(kColumnParameter, QHeaderView::Stretch);
    for (int column : {kColumnNow, kColumnLower, kColumnUpper}) {
        m_parameters->horizontalHeader()->setSectionResizeMode(column, QHeaderView::Interactive);
        m_parameters->setColumnWidth(column, m_parameters->fontMetrics().horizontalAdvance("0.00000") + 12);
    }
    // At least five rows show; more scroll inside the table.
    m_parameters->setMinimumHeight(m_parameters->horizontalHeader()->sizeHint().height() +
                                   5 * m_parameters->verticalHeader()->defaultSectionSize() + 4);
    layout->addWidget(m_parameters, 1);

    // The run's controls stay above the results' scroll area: they never
    // scroll away or get clipped (at 1024 x 700 the pane is ~250 px wide),
    // Fit and Cancel on a row of their own, the starts and progress below.
    auto* controls = new QWidget;
    controls->setObjectName("match_run_controls");
    auto* controls_layout = new QVBoxLayout(controls);
    controls_layout->setContentsMargins(4, 4, 4, 0);
    auto* run_row = new QHBoxLayout;
    m_run = new QPushButton(tr("Fit"));
    m_run->setObjectName("match_run");
    m_cancel = new QPushButton(tr("Cancel"));
    m_cancel->setObjectName("match_cancel");
    m_cancel->setEnabled(false);
    run_row->addWidget(m_run);
    run_row->addWidget(m_cancel);
    run_row->addStretch(1);
    controls_layout->addLayout(run_row);
    auto* starts_row = new QHBoxLayout;
    m_starts = new QSpinBox;
    m_starts->setObjectName("match_starts");
    m_starts->setPrefix(tr("starts "));  // no label beside it: the row fits a narrow pane
    m_starts->setRange(1, 200);
    m_starts->setValue(8);
    m_starts->setToolTip(
        tr("Multi-start points spread over the bounds: more finds other minima, costs time"));
    starts_row->addWidget(m_starts);
    m_progress = new QProgressBar;
    m_progress->setObjectName("match_progress");
    m_progress->setRange(0, 1000);
    m_progress->setTextVisible(false);
    m_progress->setMaximumHeight(8);
    m_progress->setMinimumWidth(24);  // takes what the row has left: the row asks no more than Fit and Cancel
    starts_row->addWidget(m_progress, 1);
    controls_layout->addLayout(starts_row);

    auto* results = new QWidget;
    layout = new QVBoxLayout(results);
    layout->setContentsMargins(4, 4, 4, 4);
    m_curve = new CostCurve;
    layout->addWidget(m_curve);

    m_status = new QLabel(tr("Choose a measurement, tick the fields to fit, then Fit."));
    m_status->setObjectName("match_status");
    m_status->setWordWrap(true);
    layout->addWidget(m_status);

    m_warnings = new QLabel;
    m_warnings->setObjectName("match_warnings");
    m_warnings->setWordWrap(true);
    m_warnings->setStyleSheet("color: #a04000;");
    m_warnings->hide();
    layout->addWidget(m_warnings);

    m_fitted = makeTable({tr("Parameter"), tr("Fitted"), tr("± 1σ"), tr("Note")}, "match_fitted");
    layout->addWidget(m_fitted, 1);
    m_geometries = makeTable({tr("Geometry"), tr("ΔE00"), tr("Measured L*a*b*"), tr("Fitted L*a*b*")},
                             "match_geometries");
    layout->addWidget(m_geometries, 1);
    m_alternatives = new QLabel;
    m_alternatives->setObjectName("match_alternatives");
    m_alternatives->setWordWrap(true);
    m_alternatives->hide();
    layout->addWidget(m_alternatives);

    m_accept = new QPushButton(tr("Accept as new version"));
    m_accept->setObjectName("match_accept");
    m_accept->setEnabled(false);
    m_accept->setToolTip(
        tr("Edit the recipe to the fitted values and save it as a new version (Undo reverts the edit)"));
    layout->addWidget(m_accept);

    m_split = new SplitSphereView;
    m_splitter = new QSplitter(Qt::Vertical);
    m_splitter->setObjectName("match_panes");
    m_splitter->setChildrenCollapsible(false);
    m_splitter->addWidget(scrollingPane(setup, "match_setup"));
    auto* results_pane = new QWidget;
    auto* results_layout = new QVBoxLayout(results_pane);
    results_layout->setContentsMargins(0, 0, 0, 0);
    results_layout->setSpacing(0);
    results_layout->addWidget(controls);
    results_layout->addWidget(scrollingPane(results, "match_results"), 1);
    m_splitter->addWidget(results_pane);
    m_splitter->addWidget(m_split);
    // The choices get the most room: at 1024 x 700 with a BRDF measurement
    // (a 658 px bottom tab, 131 px of it the sphere) 329 px hold the
    // parameter table without scrolling sideways, and 198 px still hold Fit
    // and Cancel (174).
    m_splitter->setStretchFactor(0, 5);
    m_splitter->setStretchFactor(1, 3);
    m_splitter->setStretchFactor(2, 2);
    setWidget(m_splitter);

    connect(import, &QPushButton::clicked, this, &MatchDock::importFile);
    connect(m_run, &QPushButton::clicked, this, &MatchDock::run);
    connect(m_cancel, &QPushButton::clicked, this, &MatchDock::cancel);
    connect(m_measurement, &QComboBox::currentIndexChanged, this, [this]() {
        refreshSplitView();
        emit measuredChanged();
    });
    connect(m_accept, &QPushButton::clicked, this, [this]() {
        if (!m_result) return;
        QStringList names;
        for (const auto& m : m_fitted_measurements) names << QString::fromStdString(m.name);
        double worst = 0.0;
        for (const auto& g : m_result->geometries) worst = std::max(worst, g.delta_e00);
        const QString note =
            m_result->geometries.empty()
                ? tr("fitted to %1").arg(names.join(", "))
                : tr("fitted to %1 (worst ΔE00 %2)").arg(names.join(", ")).arg(worst, 0, 'f', 2);
        emit acceptRequested(m_result->recipe, note);
    });
    connect(m_runner, &FitRunner::progressed, this, &MatchDock::showProgress);
    connect(m_runner, &FitRunner::finished, this, &MatchDock::showResult);
    connect(m_runner, &FitRunner::failed, this, [this](const QString& message) {
        setRunning(false);
        showMessage(message, true);
    });
    connect(m_runner, &FitRunner::cancelled, this, [this]() {
        setRunning(false);
        showMessage(tr("Fit cancelled: nothing changed."), false);
    });
    connect(m_document, &RecipeDocument::recipeLoaded, this, [this]() {
        fillParameters();
        refreshSplitView();
    });
    connect(m_document, &RecipeDocument::recipeChanged, this, [this](bool interactive) {
        if (interactive) return;
        fillParameters();
        refreshSplitView();
    });
    setMeasurements({});
    fillParameters();
}

MatchDock::~MatchDock() = default;

void MatchDock::setMeasurements(std::vector<db::Measurement> measurements) {
    // Files read in the dock stay listed after the database's.
    std::vector<db::Measurement> files;
    for (std::size_t i = 0; i < m_measurements.size(); ++i)
        if (m_from_file[i]) files.push_back(m_measurements[i]);
    m_measurements = std::move(measurements);
    m_from_file.assign(m_measurements.size(), false);
    for (auto& f : files) {
        m_measurements.push_back(std::move(f));
        m_from_file.push_back(true);
    }
    rebuildMeasurementBoxes();
}

void MatchDock::addFileMeasurement(db::Measurement measurement) {
    // Reading a file of the same name again replaces it.
    for (std::size_t i = m_measurements.size(); i-- > 0;)
        if (m_from_file[i] && m_measurements[i].name == measurement.name) {
            m_measurements.erase(m_measurements.begin() + static_cast<std::ptrdiff_t>(i));
            m_from_file.erase(m_from_file.begin() + static_cast<std::ptrdiff_t>(i));
        }
    m_measurements.push_back(std::move(measurement));
    m_from_file.push_back(true);
    rebuildMeasurementBoxes();
    m_measurement->setCurrentIndex(m_measurement->count() - 1);
}

void MatchDock::rebuildMeasurementBoxes() {
    // The choice is kept by its label where it still exists.
    const QString top = m_measurement->currentText();
    const QString bottom = m_bottom->currentText();
    for (QComboBox* box : {m_measurement, m_bottom}) {
        const QSignalBlocker block(box);
        box->clear();
        box->addItem(box == m_measurement ? tr("(choose a measurement)") : tr("(none)"), -1);
        for (std::size_t i = 0; i < m_measurements.size(); ++i) {
            const auto& m = m_measurements[i];
            QString label =
                QString::fromStdString(m.name) + (m.kind == db::MeasurementKind::MultiAngle
                                                      ? tr(" (multi-angle, %1)").arg(m.readings.size())
                                                      : tr(" (BRDF, %1 samples)").arg(m.samples.size()));
            if (m_from_file[i]) label += tr(", file");
            box->addItem(label, static_cast<int>(i));
        }
    }
    m_measurement->setCurrentIndex(std::max(0, m_measurement->findText(top)));
    m_bottom->setCurrentIndex(std::max(0, m_bottom->findText(bottom)));
    refreshSplitView();
    emit measuredChanged();
}

const db::Measurement* MatchDock::chosen(const QComboBox* box) const {
    const int index = box->currentData().toInt();
    if (index < 0 || static_cast<std::size_t>(index) >= m_measurements.size()) return nullptr;
    return &m_measurements[static_cast<std::size_t>(index)];
}

void MatchDock::importFile() {
    const auto chosen = chooseFileToOpen(
        this, QStringLiteral("match_import_dialog"), tr("Measurement file"),
        QStringLiteral("measurements/lastFolder"),
        plugins::offeredFormats(plugins::Registry::global(), plugins::OfferKind::MeasurementImport));
    if (chosen) readFile(chosen->path, chosen->format_id);
}

bool MatchDock::readFile(const QString& file, const std::optional<std::string>& format_id) {
    try {
        db::ImportOptions options;
        options.measurement.name = QFileInfo(file).completeBaseName().toStdString();
        addFileMeasurement(plugins::readMeasurementFile(file.toStdString(), options, 0, format_id));
        showMessage(tr("Read %1.").arg(QFileInfo(file).fileName()), false);
        return true;
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(e.what()), true);
        return false;
    }
}

void MatchDock::fillParameters() {
    // Ticks and typed bounds survive a refresh (by path), as long as the path exists.
    struct Choice {
        bool free;
        QString lower, upper;
    };
    std::map<QString, Choice> kept;
    for (int row = 0; row < m_parameters->rowCount(); ++row) {
        const auto* item = m_parameters->item(row, kColumnParameter);
        const QString path = item->data(kPathRole).toString();
        if (path.isEmpty()) continue;  // a group's title row
        kept[path] = {item->checkState() == Qt::Checked, m_parameters->item(row, kColumnLower)->text(),
                      m_parameters->item(row, kColumnUpper)->text()};
    }
    m_parameters->clearSpans();
    m_parameters->setRowCount(0);
    if (!m_document->hasRecipe()) return;
    // Grouped by where the field is ("basecoat > blue interference flake"):
    // a title row per group, the field's own name in its row, so that the
    // names stay readable in a narrow column.
    const auto paths = fit::listParameterPaths(m_document->recipe());
    QString group;
    for (const auto& p : paths) {
        const QString path = QString::fromStdString(p.path);
        const QString label = QString::fromStdString(p.label);
        const auto split = label.lastIndexOf(QStringLiteral(" > "));
        const QString where = split < 0 ? QString() : label.left(split);
        const QString field = split < 0 ? label : label.mid(split + 3);
        if (where != group || m_parameters->rowCount() == 0) {
            group = where;
            const int title_row = m_parameters->rowCount();
            m_parameters->insertRow(title_row);
            auto* title = new QTableWidgetItem(where.isEmpty() ? tr("Recipe") : where);
            title->setFlags(Qt::ItemIsEnabled);
            QFont bold = title->font();
            bold.setBold(true);
            title->setFont(bold);
            title->setToolTip(title->text());
            m_parameters->setItem(title_row, kColumnParameter, title);
            m_parameters->setSpan(title_row, kColumnParameter, 1, 4);
        }
        const int row = m_parameters->rowCount();
        m_parameters->insertRow(row);
        auto* name = new QTableWidgetItem(field);
        name->setData(kPathRole, path);
        name->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable | Qt::ItemIsSelectable);
        const fit::FitBounds bounds = fit::defaultFitBounds(p);
        name->setToolTip(
            tr("%1\n%2\nunit %3, allowed %4 to %5")
                .arg(label, path,
                     QString::fromUtf8(p.decl->unit.data(), static_cast<int>(p.decl->unit.size())),
                     number(p.min), number(p.max)));
        const auto old = kept.find(path);
        name->setCheckState(old != kept.end() && old->second.free ? Qt::Checked : Qt::Unchecked);
        m_parameters->setItem(row, kColumnParameter, name);
        // Four significant digits fit the column (elided in the middle, 10.0627
        // read "10…27", like a range); the tooltip has every digit.
        auto* now = new QTableWidgetItem(QString::number(p.value, 'g', 4));
        now->setToolTip(number(p.value));
        now->setFlags(Qt::ItemIsEnabled);
        m_parameters->setItem(row, kColumnNow, now);
        auto* lower = new QTableWidgetItem(old != kept.end() ? old->second.lower : QString());
        lower->setToolTip(tr("Lower bound (empty: %1)").arg(number(bounds.lower)));
        m_parameters->setItem(row, kColumnLower, lower);
        auto* upper = new QTableWidgetItem(old != kept.end() ? old->second.upper : QString());
        upper->setToolTip(tr("Upper bound (empty: %1)").arg(number(bounds.upper)));
        m_parameters->setItem(row, kColumnUpper, upper);
    }
}

bool MatchDock::freeParameter(const QString& path, std::optional<double> lower, std::optional<double> upper) {
    for (int row = 0; row < m_parameters->rowCount(); ++row) {
        auto* item = m_parameters->item(row, kColumnParameter);
        if (item->data(kPathRole).toString() != path) continue;
        item->setCheckState(Qt::Checked);
        if (lower) m_parameters->item(row, kColumnLower)->setText(number(*lower));
        if (upper) m_parameters->item(row, kColumnUpper)->setText(number(*upper));
        return true;
    }
    return false;
}

fit::FitProblem MatchDock::problem() const {
    if (!m_document->hasRecipe()) throw InputError("Match", "recipe", "open a recipe to use as the template");
    const db::Measurement* top = chosen(m_measurement);
    if (top == nullptr) throw InputError("Match", "measurement", "choose the measurement to match");
    fit::FitProblem problem;
    problem.recipe = m_document->recipe();
    db::addFitObservation(problem.observations, *top, fit::Side::Top);
    if (const db::Measurement* bottom = chosen(m_bottom))
        db::addFitObservation(problem.observations, *bottom, fit::Side::Bottom);
    for (int row = 0; row < m_parameters->rowCount(); ++row) {
        const auto* item = m_parameters->item(row, kColumnParameter);
        if (item->data(kPathRole).toString().isEmpty() || item->checkState() != Qt::Checked) continue;
        fit::FreeParameter p;
        p.path = item->data(kPathRole).toString().toStdString();
        p.lower = parseBound(m_parameters->item(row, kColumnLower)->text(), p.path + " (lower bound)");
        p.upper = parseBound(m_parameters->item(row, kColumnUpper)->text(), p.path + " (upper bound)");
        problem.free.push_back(std::move(p));
    }
    if (problem.free.empty()) throw InputError("Match", "parameters", "tick at least one field to fit");
    problem.settings.starts = m_starts->value();
    return problem;
}

void MatchDock::run() {
    if (running()) return;
    fit::FitProblem p;
    try {
        p = problem();
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(e.what()), true);
        return;
    }
    m_fitted_measurements.clear();
    if (const auto* top = chosen(m_measurement)) m_fitted_measurements.push_back(*top);
    if (const auto* bottom = chosen(m_bottom)) m_fitted_measurements.push_back(*bottom);
    m_last_problem = p;
    m_result.reset();
    m_curve->clear();
    m_progress->setValue(0);
    setRunning(true);
    showMessage(tr("Fitting..."), false);
    m_runner->start(std::move(p));
}

void MatchDock::cancel() { m_runner->cancel(); }

bool MatchDock::running() const { return m_runner->running(); }

void MatchDock::setRunning(bool running) {
    // The button about to be disabled hands its focus to the other one:
    // Qt would give it to the next widget in the chain, and the results
    // pane would scroll to it, taking Cancel out of view.
    QPushButton* on = running ? m_cancel : m_run;
    QPushButton* off = running ? m_run : m_cancel;
    on->setEnabled(true);
    if (off->hasFocus()) on->setFocus();
    off->setEnabled(false);
    m_parameters->setEnabled(!running);
    m_measurement->setEnabled(!running);
    m_bottom->setEnabled(!running);
    if (running) m_accept->setEnabled(false);
}

void MatchDock::showMessage(const QString& text, bool error) {
    m_status->setText(text);
    m_status->setStyleSheet(error ? "color: #b00020;" : QString());
}

void MatchDock::showProgress(const fit::FitProgress& p) {
    m_progress->setValue(static_cast<int>(std::lround(1000.0 * std::clamp(p.fraction, 0.0, 1.0))));
    m_curve->add(p.evaluations, p.best_cost);
    showMessage(tr("%1 %2 of %3: best cost %4, %5 evaluations")
                    .arg(QString::fromStdString(p.stage))
                    .arg(p.start)
                    .arg(p.starts)
                    .arg(p.best_cost, 0, 'g', 4)
                    .arg(p.evaluations),
                false);
}

void MatchDock::showResult(std::shared_ptr<const fit::FitResult> result) {
    setRunning(false);
    m_result = std::move(result);
    const fit::FitResult& r = *m_result;
    m_progress->setValue(1000);
    for (double c : r.cost_history) m_curve->add(r.evaluations, c);

    m_fitted->setRowCount(static_cast<int>(r.parameters.size()));
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
        const auto& p = r.parameters[i];
        const int row = static_cast<int>(i);
        // The field's own name (as in the parameter table); where it is, in the tooltip.
        const QString label = QString::fromStdString(p.label);
        auto* name = new QTableWidgetItem(label.section(QStringLiteral(" > "), -1));
        name->setToolTip(label + "\n" + QString::fromStdString(p.path));
        m_fitted->setItem(row, 0, name);
        m_fitted->setItem(row, 1,
                          new QTableWidgetItem(number(p.value) + " " + QString::fromStdString(p.unit)));
        m_fitted->setItem(
            row, 2, new QTableWidgetItem(std::isfinite(p.sigma) ? number(p.sigma) : tr("not determined")));
        QString note;
        if (p.at_bound) note = tr("at its bound (%1 to %2)").arg(number(p.lower), number(p.upper));
        if (!p.determined) note = note.isEmpty() ? tr("not determined") : note + tr("; not determined");
        m_fitted->setItem(row, 3, new QTableWidgetItem(note));
    }
    m_geometries->setRowCount(static_cast<int>(r.geometries.size()));
    double worst = 0.0;
    QString worst_at;
    for (std::size_t i = 0; i < r.geometries.size(); ++i) {
        const auto& g = r.geometries[i];
        const int row = static_cast<int>(i);
        m_geometries->setItem(row, 0, new QTableWidgetItem(geometryName(g)));
        m_geometries->setItem(row, 1, new QTableWidgetItem(QString::number(g.delta_e00, 'f', 2)));
        m_geometries->setItem(row, 2, new QTableWidgetItem(labText(g.measured)));
        m_geometries->setItem(row, 3, new QTableWidgetItem(labText(g.fitted)));
        if (g.delta_e00 >= worst) {
            worst = g.delta_e00;
            worst_at = geometryName(g);
        }
    }
    QString verdict =
        r.geometries.empty()
            ? tr("Fitted: cost %1 over %2 residuals").arg(r.cost, 0, 'g', 4).arg(r.residual_count)
            : tr("Fitted: worst ΔE00 %1 at %2").arg(worst, 0, 'f', 2).arg(worst_at);
    verdict += tr(" (reduced χ² %1; %2 evaluations in %3 s).")
                   .arg(r.reduced_chi_square, 0, 'g', 3)
                   .arg(r.evaluations)
                   .arg(r.seconds, 0, 'f', 1);
    // A reduced chi-square far above 1: the residuals are not noise, the
    // structure of the template cannot reach the measurement.
    if (r.reduced_chi_square > 4.0)
        verdict +=
            tr(" The template cannot reproduce this measurement within its noise: try another structure "
               "(more layers, a depth profile) or free more fields.");
    showMessage(verdict, false);

    QStringList warnings;
    for (const auto& issue : r.identifiability) warnings << QString::fromStdString(issue.message);
    m_warnings->setText(warnings.join("\n"));
    m_warnings->setVisible(!warnings.isEmpty());
    if (r.alternatives.empty()) {
        m_alternatives->hide();
    } else {
        QStringList lines{
            tr("%n other recipe(s) look nearly the same:", nullptr, static_cast<int>(r.alternatives.size()))};
        for (const auto& a : r.alternatives) {
            QStringList values;
            for (std::size_t i = 0; i < a.values.size() && i < r.parameters.size(); ++i)
                values << QStringLiteral("%1 = %2").arg(QString::fromStdString(r.parameters[i].label),
                                                        number(a.values[i]));
            lines << tr("cost %1, worst ΔE00 %2: %3")
                         .arg(a.cost, 0, 'g', 4)
                         .arg(a.max_delta_e00, 0, 'f', 2)
                         .arg(values.join(", "));
        }
        m_alternatives->setText(lines.join("\n"));
        m_alternatives->show();
    }
    m_accept->setEnabled(true);
    refreshSplitView();
}

void MatchDock::refreshSplitView() {
    const db::Measurement* m = chosen(m_measurement);
    // The split view's pane is there for a BRDF measurement only: the other
    // panes get its room otherwise, and give it a share back when it comes.
    const bool split = m != nullptr && m->kind == db::MeasurementKind::Brdf;
    if (split != m_split->isVisibleTo(this)) {
        m_split->setVisible(split);
        const bool across = m_splitter->orientation() == Qt::Horizontal;
        const int extent = across ? m_splitter->width() : m_splitter->height();
        // Side by side the sphere needs no more width than the dock's height.
        // The rest 5 : 3, as the stretch factors: the choices' table is the wider.
        const int sphere = across ? std::min(extent / 5, m_splitter->height()) : extent / 4;
        const int choices = (extent - sphere) * 5 / 8;
        if (split && extent > 0) m_splitter->setSizes({choices, extent - sphere - choices, sphere});
    }
    if (m == nullptr) {
        m_split->showMessage(tr("Choose a BRDF measurement for the split view of measured against fitted."));
        return;
    }
    if (m->kind != db::MeasurementKind::Brdf) {
        m_split->showMessage(tr("The split view shades a BRDF measurement; '%1' is a multi-angle reading "
                                "(its spectra and flop path are on the plots).")
                                 .arg(QString::fromStdString(m->name)));
        return;
    }
    // The fitted recipe once this measurement has been fitted; the edited one before.
    const bool fitted = m_result && !m_fitted_measurements.empty() && m_fitted_measurements.front() == *m;
    if (!fitted && !m_document->hasRecipe()) {
        m_split->showMessage(tr("Open a recipe to compare with the measurement."));
        return;
    }
    m_split->shade(std::make_shared<const db::Measurement>(*m),
                   fitted ? m_result->recipe : m_document->recipe(), fitted ? tr("fitted") : tr("recipe"));
}

void MatchDock::resizeEvent(QResizeEvent* event) {
    QDockWidget::resizeEvent(event);
    // Side by side where the dock is much wider than tall (a bottom tab), stacked otherwise.
    const Qt::Orientation wanted = width() >= 3 * height() / 2 ? Qt::Horizontal : Qt::Vertical;
    if (m_splitter->orientation() == wanted) return;
    m_splitter->setOrientation(wanted);
    const int extent = wanted == Qt::Horizontal ? m_splitter->width() : m_splitter->height();
    m_splitter->setSizes({extent * 45 / 100, extent * 33 / 100, extent * 22 / 100});
}

std::optional<MultiAngleReport> MatchDock::measuredReport() const {
    const db::Measurement* m = chosen(m_measurement);
    if (m == nullptr || m->kind != db::MeasurementKind::MultiAngle) return std::nullopt;
    MultiAngleReport report;
    report.illuminant = db::measurementIlluminant(*m);
    report.observer = db::measurementObserver(*m);
    // The plots' flop (a*b* travel, spectra) is the 45° in-plane series;
    // readings at other illuminations or out of the plane would sit on it at
    // their aspecular angle alone. They are in the geometry table after a fit.
    for (const auto& r : m->readings) {
        if (r.illumination_deg != kMultiAngleIlluminationDeg || !isInPlane(r.azimuth_deg)) continue;
        MultiAngleColour c;
        c.aspecular_deg = r.aspecular_deg;
        c.lab = Lab{r.L, r.a, r.b};
        c.reflectance_factor = r.reflectance;
        report.colours.push_back(std::move(c));
    }
    if (report.colours.empty()) return std::nullopt;
    return report;
}

std::vector<double> MatchDock::measuredWavelengths() const {
    const db::Measurement* m = chosen(m_measurement);
    if (m == nullptr || m->kind != db::MeasurementKind::MultiAngle) return {};
    return m->wavelengths_nm;
}

QString MatchDock::measuredName() const {
    const db::Measurement* m = chosen(m_measurement);
    return m == nullptr ? QString() : QString::fromStdString(m->name);
}

}  // namespace paintlab::gui
