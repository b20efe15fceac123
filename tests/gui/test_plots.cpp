// The workstation's plots under a virtual X server (tests/gui/CMakeLists.txt
// runs this in xvfb-run): every plot draws the pearlescent demo paint, their
// CSV data agree with the engine evaluated here directly (LayeredBrdf::eval
// through reflectanceFactorColour, multiAngleColours: an independent truth,
// not the plots' own numbers), the a*b* path has the six geometries in
// aspecular order, a changed recipe changes the data, comparisons overlay a
// second series, PNG export writes an image of the widget's size, the lobe
// rotates with the mouse, and the main window's Plots dock follows the
// scheduler. Issue 27 (items 9-12): no negative reflectance drawn without a
// word, log axes that keep the curves (in-plane and paint spectra), legends
// outside the data, an a*b* chart with equal scales and separate labels, axis
// titles that fit, a comparison on the paint spectra too; each read back from
// the chart's own layout (PlotWidget::chartLayout). Screenshots of each plot
// go to the build directory (screenshots/plots_*.png); baselines are not
// compared here.
//
// The BRDFs use the preview preset: quick under ASan, and the plots do not
// depend on the preset. Times are printed, not asserted (docs/PERFORMANCE.md).

#include "ab_chart.h"
#include "gui_test_main.h"
#include "inplane_plot.h"
#include "lobe_plot.h"
#include "main_window.h"
#include "plot_data.h"
#include "plot_render_thread.h"
#include "plot_test_support.h"
#include "plots_dock.h"
#include "spectra_plot.h"
#include "spectrum_chart.h"
#include "workstation_fixture.h"

#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"

#include <QApplication>
#include <QCheckBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <variant>

using namespace paintlab;
using namespace paintlab::gui;
using paintlab::test::Csv;
using paintlab::test::pearlRecipe;
using paintlab::test::readCsv;
using paintlab::test::silverRecipe;

namespace {

constexpr int kWaitMs = test::kGuiWaitMs;
const QString kPearl = QStringLiteral("Blue pearl over black (two layers)");

// The same paint with half the pearl flakes.
Recipe fewerFlakes(Recipe recipe) {
    for (Layer& layer : recipe.layers)
        for (Component& c : layer.components)
            if (auto* flake = std::get_if<InterferenceFlake>(&c)) flake->volume_fraction *= 0.5;
    return recipe;
}

bool near(double got, double want) { return std::abs(got - want) <= 1e-9 * std::abs(want) + 1e-12; }

// Pixels that differ from the most common colour (the background), and how many colours there are.
struct PixelStats {
    qsizetype foreground = 0;
    qsizetype colours = 0;
    qsizetype total = 0;
};
PixelStats pixelStats(const QImage& image) {
    std::map<QRgb, qsizetype> histogram;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) ++histogram[rgb.pixel(x, y)];
    qsizetype background = 0;
    for (const auto& [colour, count] : histogram) background = std::max(background, count);
    const qsizetype total = qsizetype(rgb.width()) * rgb.height();
    return {total - background, static_cast<qsizetype>(histogram.size()), total};
}

QString screenshotDir() {
    QDir().mkpath(QStringLiteral(PAINTLAB_SCREENSHOT_DIR));
    return QStringLiteral(PAINTLAB_SCREENSHOT_DIR);
}

}  // namespace

class PlotsTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void eachPlotDrawsThePearlescentPaint();
    void inplaneCsvMatchesTheEngine();
    void abChartHasTheSixGeometriesInAspecularOrder();
    void abCsvMatchesTheEngine();
    void lobeCsvMatchesTheEngine();
    void ingredientSpectraAreTheRecipes();
    void changingTheRecipeChangesTheData();
    void comparisonIsASecondDashedSeries();
    void pngExportWritesAnImageOfTheWidgetsSize();
    void lobeRotatesWithTheMouseAndFollowsTheIncidence();
    void logScaleRedraws();
    void inplaneShowsNoUnexplainedNegativeValue();
    void logScaleDrawsTheInplaneCurvesAndThePaintSpectra();
    void legendsAreOutsideTheData();
    void abChartHasEqualScalesAndSeparateLabels();
    void axisTitlesFit();
    void dockComparisonIsOnThePaintSpectraToo();
    void mainWindowPlotsDockFollowsTheRecipe();
    void cleanupTestCase();

private:
    // The plots, each a top-level window of a fixed size so screenshots compare.
    template <class Plot> Plot* shown(std::unique_ptr<Plot>& plot, const char* name);
    void verifyInplaneCsv(const QString& path, const LayeredBrdf& brdf, const QString& series);
    void verifyAbCsv(const QString& path, const LayeredBrdf& brdf, const QString& series);

    QTemporaryDir m_dir;
    std::shared_ptr<const LayeredBrdf> m_pearl;
    std::shared_ptr<const LayeredBrdf> m_fewer;
    std::unique_ptr<InplanePlot> m_inplane;
    std::unique_ptr<LobePlot> m_lobe;
    std::unique_ptr<SpectraPlot> m_paint_spectra;
    std::unique_ptr<SpectraPlot> m_ingredient_spectra;
    std::unique_ptr<AbChart> m_ab;
};

template <class Plot> Plot* PlotsTest::shown(std::unique_ptr<Plot>& plot, const char* name) {
    if (!plot) {
        plot = std::make_unique<Plot>();
        plot->setObjectName(name);
        plot->setWindowTitle(name);
        plot->resize(720, 480);
        plot->show();
        if (!QTest::qWaitForWindowExposed(plot.get())) return nullptr;
    }
    return plot.get();
}

void PlotsTest::initTestCase() {
    QVERIFY(m_dir.isValid());
    m_pearl = std::make_shared<const LayeredBrdf>(
        computeLayeredBrdf(pearlRecipe(), presetSettings(Preset::Preview)));
    m_fewer = std::make_shared<const LayeredBrdf>(
        computeLayeredBrdf(fewerFlakes(pearlRecipe()), presetSettings(Preset::Preview)));
    QVERIFY(shown(m_inplane, "inplane") != nullptr);
    QVERIFY(shown(m_lobe, "lobe") != nullptr);
    QVERIFY(shown(m_paint_spectra, "paint_spectra") != nullptr);
    QVERIFY(shown(m_ingredient_spectra, "ingredient_spectra") != nullptr);
    QVERIFY(shown(m_ab, "ab") != nullptr);
    m_inplane->setIncidences({15.0, 30.0, 45.0, 60.0, 75.0});
    m_inplane->setBrdf(m_pearl);
    m_lobe->setBrdf(m_pearl);
    m_paint_spectra->setBrdf(*m_pearl);
    m_ingredient_spectra->setSpectra(recipeSpectra(pearlRecipe()), QStringLiteral("Pearl ingredients"));
    m_ab->setBrdf(*m_pearl);
    qInfo("lobe grid %.1f ms, lobe update (grid + VTK geometry) %.1f ms", m_lobe->grid().seconds * 1e3,
          m_lobe->lastUpdateMs());
}

void PlotsTest::eachPlotDrawsThePearlescentPaint() {
    const std::vector<std::pair<PlotWidget*, const char*>> plots{
        {m_inplane.get(), "plots_inplane"},
        {m_lobe.get(), "plots_lobe"},
        {m_paint_spectra.get(), "plots_paint_spectra"},
        {m_ingredient_spectra.get(), "plots_ingredient_spectra"},
        {m_ab.get(), "plots_ab"}};
    qInfo("plots drawn on %s", PlotRenderThread::instance().threaded()
                                   ? "the plot render thread"
                                   : "the GUI thread (no threaded OpenGL)");
    for (const auto& [plot, name] : plots) {
        QVERIFY2(plot->failure().isEmpty(), qPrintable(plot->failure()));
        const QImage image = plot->renderImage();
        QVERIFY2(!image.isNull(), name);
        QVERIFY(image.save(screenshotDir() + "/" + name + ".png"));
        const PixelStats s = pixelStats(image);
        // Axes, labels and curves cover well over 1 % of the widget, in many colours (antialiasing).
        QVERIFY2(
            s.foreground > s.total / 100,
            qPrintable(QStringLiteral("%1: %2 of %3 pixels drawn").arg(name).arg(s.foreground).arg(s.total)));
        QVERIFY2(s.colours > 20, qPrintable(QStringLiteral("%1: %2 colours").arg(name).arg(s.colours)));
        // The first draw compiles shaders and rasterises glyphs; later ones are what an update costs.
        const double first = plot->lastPaintMs();
        plot->renderImage();
        qInfo("%s: draw %.1f ms (first), %.1f ms (next) at %dx%d on the plot render thread", name, first,
              plot->lastPaintMs(), image.width(), image.height());
    }
    // The blue pearl's lobe is blue where it is bright: many more bluish than reddish pixels.
    const QImage lobe = m_lobe->renderImage().convertToFormat(QImage::Format_RGB32);
    qsizetype blue = 0;
    qsizetype red = 0;
    for (int y = 0; y < lobe.height(); ++y)
        for (int x = 0; x < lobe.width(); ++x) {
            const QColor c = lobe.pixelColor(x, y);
            if (c.blue() > c.red() + 40 && c.blue() > c.green() + 10) ++blue;
            if (c.red() > c.blue() + 40) ++red;
        }
    QVERIFY2(blue > 500 && blue > 4 * red, qPrintable(QStringLiteral("blue %1, red %2").arg(blue).arg(red)));
    // Upright, as on screen: the lobe's gradient background runs from white at
    // the bottom to grey-blue (0.86, 0.89, 0.93) at the top, and an image read
    // back from OpenGL bottom row first would show it the other way up.
    const QColor top = lobe.pixelColor(2, 2);
    const QColor bottom = lobe.pixelColor(2, lobe.height() - 3);
    QVERIFY2(top.red() < 235 && bottom.red() > 245,
             qPrintable(QStringLiteral("top red %1, bottom red %2").arg(top.red()).arg(bottom.red())));
}

void PlotsTest::verifyInplaneCsv(const QString& path, const LayeredBrdf& brdf, const QString& series) {
    const Csv csv = readCsv(path);
    QCOMPARE(csv.header, QStringList({"series", "theta_i_deg", "view_deg", "R", "G", "B", "Y"}));
    std::size_t checked = 0;
    std::map<double, int> per_incidence;
    for (std::size_t k = 0; k < csv.rows.size(); ++k) {
        if (csv.rows[k][0] != series) continue;
        const double theta_i = csv.number(k, "theta_i_deg");
        const double view = csv.number(k, "view_deg");
        ++per_incidence[theta_i];
        // The light at azimuth 180; positive view angles on the far (mirror) side.
        const Direction wi = directionFromAnglesDeg(theta_i, 180.0);
        const Direction wo = directionFromAnglesDeg(std::abs(view), view >= 0.0 ? 0.0 : 180.0);
        const SpectralColour c = reflectanceFactorColour(brdf, wi, wo);
        const double want[4] = {c.linear_srgb.r, c.linear_srgb.g, c.linear_srgb.b, c.xyz.Y};
        const char* names[4] = {"R", "G", "B", "Y"};
        for (int i = 0; i < 4; ++i)
            QVERIFY2(near(csv.number(k, names[i]), want[i]),
                     qPrintable(QStringLiteral("%1 at theta_i %2, view %3: %4, engine %5")
                                    .arg(names[i])
                                    .arg(theta_i)
                                    .arg(view)
                                    .arg(csv.number(k, names[i]), 0, 'g', 17)
                                    .arg(want[i], 0, 'g', 17)));
        ++checked;
    }
    QCOMPARE(per_incidence.size(), std::size_t{5});  // 15, 30, 45, 60, 75
    for (const auto& [theta_i, count] : per_incidence) QCOMPARE(count, 69);
    QCOMPARE(checked, std::size_t{5 * 69});
}

void PlotsTest::inplaneCsvMatchesTheEngine() {
    const QString path = m_dir.filePath("inplane.csv");
    QVERIFY(m_inplane->exportCsv(path));
    verifyInplaneCsv(path, *m_pearl, QStringLiteral("current"));
    // curve() is still the 45 degree curve (test_workstation relies on it): its peak is the mirror direction.
    QCOMPARE(m_inplane->curve().theta_i_deg, 45.0);
}

void PlotsTest::abChartHasTheSixGeometriesInAspecularOrder() {
    const std::vector<double> want(kAspecularAnglesDeg.begin(), kAspecularAnglesDeg.end());
    QCOMPARE(m_ab->pathAspecularDeg(), want);  // what the chart joins, read from its own table
    QCOMPARE(m_ab->report().colours.size(), std::size_t{6});
    const QString path = m_dir.filePath("ab.csv");
    QVERIFY(m_ab->exportCsv(path));
    const Csv csv = readCsv(path);
    QCOMPARE(csv.rows.size(), std::size_t{6});
    for (std::size_t k = 0; k < 6; ++k) QCOMPARE(csv.number(k, "aspecular_deg"), want[k]);
}

void PlotsTest::verifyAbCsv(const QString& path, const LayeredBrdf& brdf, const QString& series) {
    const Csv csv = readCsv(path);
    QCOMPARE(csv.header, QStringList({"series", "aspecular_deg", "L", "a", "b", "X", "Y", "Z"}));
    const MultiAngleReport truth = multiAngleColours(brdf);
    std::size_t g = 0;
    for (std::size_t k = 0; k < csv.rows.size(); ++k) {
        if (csv.rows[k][0] != series) continue;
        QVERIFY(g < truth.colours.size());
        const MultiAngleColour& c = truth.colours[g++];
        QCOMPARE(csv.number(k, "aspecular_deg"), c.aspecular_deg);
        const double want[6] = {c.lab.L, c.lab.a, c.lab.b, c.xyz.X, c.xyz.Y, c.xyz.Z};
        const char* names[6] = {"L", "a", "b", "X", "Y", "Z"};
        for (int i = 0; i < 6; ++i)
            QVERIFY2(near(csv.number(k, names[i]), want[i]),
                     qPrintable(QStringLiteral("%1 at 45as%2: %3, engine %4")
                                    .arg(names[i])
                                    .arg(c.aspecular_deg)
                                    .arg(csv.number(k, names[i]), 0, 'g', 17)
                                    .arg(want[i], 0, 'g', 17)));
    }
    QCOMPARE(g, truth.colours.size());
}

void PlotsTest::abCsvMatchesTheEngine() {
    const QString path = m_dir.filePath("ab_truth.csv");
    QVERIFY(m_ab->exportCsv(path));
    verifyAbCsv(path, *m_pearl, QStringLiteral("current"));
}

void PlotsTest::lobeCsvMatchesTheEngine() {
    const QString path = m_dir.filePath("lobe.csv");
    QVERIFY(m_lobe->exportCsv(path));
    const Csv csv = readCsv(path);
    const LobeGrid& grid = m_lobe->grid();
    QCOMPARE(csv.rows.size(), grid.theta_o_deg.size() * grid.phi_o_deg.size());
    for (std::size_t k = 0; k < csv.rows.size(); k += 37) {  // a spread sample of the 4416 directions
        const Direction wi = directionFromAnglesDeg(csv.number(k, "theta_i_deg"), csv.number(k, "phi_i_deg"));
        const Direction wo = directionFromAnglesDeg(csv.number(k, "theta_o_deg"), csv.number(k, "phi_o_deg"));
        const SpectralColour c = reflectanceFactorColour(*m_pearl, wi, wo);
        QVERIFY2(near(csv.number(k, "Y"), c.xyz.Y) && near(csv.number(k, "B"), c.linear_srgb.b),
                 qPrintable(
                     QStringLiteral("row %1: Y %2, engine %3").arg(k).arg(csv.number(k, "Y")).arg(c.xyz.Y)));
    }
}

void PlotsTest::ingredientSpectraAreTheRecipes() {
    const std::vector<std::string> quantities = m_ingredient_spectra->quantities();
    QVERIFY(quantities.size() >= 3);  // binder index, TiO2 / mica index, carbon black absorption ...
    const std::vector<NamedSpectrum> all = recipeSpectra(pearlRecipe());
    for (const std::string& q : quantities) {
        m_ingredient_spectra->setQuantity(q);
        const QString path = m_dir.filePath("ingredients.csv");
        QVERIFY(m_ingredient_spectra->exportCsv(path));
        const Csv csv = readCsv(path);
        std::size_t rows = 0;
        for (const NamedSpectrum& s : all)
            if (s.quantity == q) rows += s.spectrum.values().size();
        QCOMPARE(csv.rows.size(), rows);
        for (const QStringList& row : csv.rows) QCOMPARE(row[1].toStdString(), q);
    }
    // The carbon black's absorption, sample for sample.
    const auto carbon = std::find_if(all.begin(), all.end(), [](const NamedSpectrum& s) {
        return s.name.find("carbon black") != std::string::npos && s.quantity.find("1/") != std::string::npos;
    });
    QVERIFY(carbon != all.end());
    m_ingredient_spectra->setQuantity(carbon->quantity);
    const std::vector<NamedSpectrum> shown = m_ingredient_spectra->shownSpectra();
    QVERIFY(std::find(shown.begin(), shown.end(), *carbon) != shown.end());
    m_ingredient_spectra->setQuantity(quantities.front());
    // Paint spectra: the reflectance factor at each geometry, as the engine's multi-angle report.
    const MultiAngleReport truth = multiAngleColours(*m_pearl);
    QCOMPARE(m_paint_spectra->shownSpectra().size(), std::size_t{6});
    for (std::size_t g = 0; g < 6; ++g)
        QVERIFY(m_paint_spectra->shownSpectra()[g].spectrum.values() == truth.colours[g].reflectance_factor);
}

void PlotsTest::changingTheRecipeChangesTheData() {
    const auto before_inplane = m_inplane->curves();
    const auto before_ab = m_ab->report().colours;
    QSignalSpy changed(m_inplane.get(), &PlotWidget::dataChanged);
    m_inplane->setBrdf(m_fewer);
    m_ab->setBrdf(*m_fewer);
    QCOMPARE(changed.count(), 1);
    QVERIFY(m_inplane->curves()[2].y != before_inplane[2].y);
    QVERIFY(m_ab->report().colours[1].lab.L != before_ab[1].lab.L);
    // Half the flakes: less light at the near-specular 45as15.
    QVERIFY(m_ab->report().colours[1].lab.L < before_ab[1].lab.L);
    const QString inplane = m_dir.filePath("inplane_fewer.csv");
    const QString ab = m_dir.filePath("ab_fewer.csv");
    QVERIFY(m_inplane->exportCsv(inplane));
    QVERIFY(m_ab->exportCsv(ab));
    verifyInplaneCsv(inplane, *m_fewer, QStringLiteral("current"));
    verifyAbCsv(ab, *m_fewer, QStringLiteral("current"));
    m_inplane->setBrdf(m_pearl);
    m_ab->setBrdf(*m_pearl);
}

void PlotsTest::comparisonIsASecondDashedSeries() {
    const QImage alone = m_inplane->renderImage();
    m_inplane->setComparison(*m_fewer, QStringLiteral("half the flakes"));
    m_ab->setComparison(*m_fewer, QStringLiteral("half the flakes"));
    QVERIFY(m_inplane->hasComparison() && m_ab->hasComparison());
    QVERIFY(m_inplane->renderImage() != alone);
    QVERIFY(m_inplane->renderImage().save(screenshotDir() + "/plots_inplane_comparison.png"));
    QVERIFY(m_ab->renderImage().save(screenshotDir() + "/plots_ab_comparison.png"));
    const QString inplane = m_dir.filePath("inplane_cmp.csv");
    const QString ab = m_dir.filePath("ab_cmp.csv");
    QVERIFY(m_inplane->exportCsv(inplane));
    QVERIFY(m_ab->exportCsv(ab));
    verifyInplaneCsv(inplane, *m_pearl, QStringLiteral("current"));
    verifyInplaneCsv(inplane, *m_fewer, QStringLiteral("half the flakes"));
    verifyAbCsv(ab, *m_pearl, QStringLiteral("current"));
    verifyAbCsv(ab, *m_fewer, QStringLiteral("half the flakes"));
    m_inplane->clearComparison();
    m_ab->clearComparison();
    QVERIFY(m_inplane->exportCsv(inplane));
    QCOMPARE(readCsv(inplane).rows.size(), std::size_t{5 * 69});
}

void PlotsTest::pngExportWritesAnImageOfTheWidgetsSize() {
    for (PlotWidget* plot : std::initializer_list<PlotWidget*>{
             m_inplane.get(), m_lobe.get(), m_paint_spectra.get(), m_ingredient_spectra.get(), m_ab.get()}) {
        const QString path = m_dir.filePath(plot->objectName() + ".png");
        QVERIFY(plot->exportPng(path));
        QImage image;
        QVERIFY(image.load(path, "PNG"));
        QCOMPARE(image.size(), plot->size() * plot->devicePixelRatio());
        QVERIFY(pixelStats(image).colours > 20);
    }
    // A file that cannot be written: false, nothing left behind.
    QVERIFY(!m_ab->exportPng(m_dir.filePath("no/such/dir/ab.png")));
    QVERIFY(!m_ab->exportCsv(m_dir.filePath("no/such/dir/ab.csv")));
}

void PlotsTest::lobeRotatesWithTheMouseAndFollowsTheIncidence() {
    const auto camera = m_lobe->cameraPosition();
    const QImage before = m_lobe->renderImage();
    const QPoint from(m_lobe->width() / 2, m_lobe->height() / 2);
    QTest::mousePress(m_lobe.get(), Qt::LeftButton, {}, from);
    for (int k = 1; k <= 10; ++k) QTest::mouseMove(m_lobe.get(), from + QPoint(8 * k, 3 * k));
    QTest::mouseRelease(m_lobe.get(), Qt::LeftButton, {}, from + QPoint(80, 30));
    QVERIFY(m_lobe->cameraPosition() != camera);
    const QImage rotated = m_lobe->renderImage();
    QVERIFY(rotated != before);
    QVERIFY(rotated.save(screenshotDir() + "/plots_lobe_rotated.png"));
    m_lobe->resetView();
    QCOMPARE(m_lobe->cameraPosition(), camera);

    m_lobe->setIncidence(20.0, 90.0);
    QCOMPARE(m_lobe->grid().theta_i_deg, 20.0);
    QCOMPARE(m_lobe->grid().phi_i_deg, 90.0);
    // The peak follows the mirror direction: theta 20, azimuth 270.
    const LobeGrid& g = m_lobe->grid();
    const auto peak = static_cast<std::size_t>(std::max_element(g.y.begin(), g.y.end()) - g.y.begin());
    QVERIFY2(std::abs(g.theta_o_deg[peak / g.phi_o_deg.size()] - 20.0) < 4.0 &&
                 std::abs(g.phi_o_deg[peak % g.phi_o_deg.size()] - 270.0) < 8.0,
             qPrintable(QStringLiteral("peak at theta %1, phi %2")
                            .arg(g.theta_o_deg[peak / g.phi_o_deg.size()])
                            .arg(g.phi_o_deg[peak % g.phi_o_deg.size()])));
    QVERIFY(m_lobe->renderImage() != before);
    m_lobe->setIncidence(45.0, 0.0);
}

void PlotsTest::logScaleRedraws() {
    const QImage inplane = m_inplane->renderImage();
    const QImage lobe = m_lobe->renderImage();
    m_inplane->setLogScale(true);
    m_lobe->setLogRadius(true);
    QVERIFY(m_inplane->renderImage() != inplane);
    QVERIFY(m_lobe->renderImage() != lobe);
    QVERIFY(m_inplane->renderImage().save(screenshotDir() + "/plots_inplane_log.png"));
    QVERIFY(m_lobe->renderImage().save(screenshotDir() + "/plots_lobe_log.png"));
    m_inplane->setLogScale(false);
    m_lobe->setLogRadius(false);
}

// Issue 27 item 9: the blue pearl's 45-degree R channel (linear sRGB) goes
// below zero (an out-of-gamut colour; the spectral BRDF is positive): it is
// drawn at zero and the chart says why; the axis names the quantity.
void PlotsTest::inplaneShowsNoUnexplainedNegativeValue() {
    const std::vector<double>& r = m_inplane->curve().r;
    const double lowest = *std::min_element(r.begin(), r.end());
    QVERIFY2(lowest < 0.0, "the blue pearl's R channel no longer goes below 0: the test needs another paint");
    for (double y : m_inplane->curve().y) QVERIFY(y >= 0.0);  // CIE Y of a positive spectrum
    m_inplane->renderImage();
    const PlotWidget::ChartLayout layout = m_inplane->chartLayout();
    QVERIFY2(layout.left_min >= 0.0, qPrintable(QStringLiteral("axis from %1").arg(layout.left_min)));
    QVERIFY2(layout.left_title.contains(QStringLiteral("reflectance factor")) &&
                 layout.left_title.contains(QString::fromUtf8("\u03c0f")),
             qPrintable(layout.left_title));
    QVERIFY2(layout.legend_labels.contains(QStringLiteral("R* (linear sRGB, 45 deg)")),
             qPrintable(layout.legend_labels.join(" | ")));
    QVERIFY2(layout.title.contains(QStringLiteral("outside the sRGB gamut")) &&
                 layout.title.contains(QStringLiteral("drawn at 0")),
             qPrintable(layout.title));
}

namespace {

// Pixels of the chart's data area (layout y up, image y down) that are not white or grey.
qsizetype colouredPixelsInData(const QImage& image, const PlotWidget::ChartLayout& layout) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const double scale = image.height() / std::max(1.0, layout.scene.height());
    qsizetype count = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QPointF at(x / scale, (rgb.height() - 1 - y) / scale);
            if (!layout.data.adjusted(2, 2, -2, -2).contains(at)) continue;
            const QColor c = rgb.pixelColor(x, y);
            const int spread =
                std::max({c.red(), c.green(), c.blue()}) - std::min({c.red(), c.green(), c.blue()});
            if (spread > 60 || std::max({c.red(), c.green(), c.blue()}) < 80) ++count;
        }
    return count;
}

}  // namespace

// Issue 27 item 11: a log axis keeps the curves (values <= 0 are dropped with
// a note), on the in-plane plot and on the paint spectra, through the dock's box.
void PlotsTest::logScaleDrawsTheInplaneCurvesAndThePaintSpectra() {
    const qsizetype linear = colouredPixelsInData(m_inplane->renderImage(), m_inplane->chartLayout());
    m_inplane->setLogScale(true);
    const QImage log_image = m_inplane->renderImage();
    const PlotWidget::ChartLayout log_layout = m_inplane->chartLayout();
    m_inplane->setLogScale(false);
    QVERIFY(log_image.save(screenshotDir() + "/plots_inplane_log_curves.png"));
    QVERIFY(log_layout.left_log);
    const qsizetype log_pixels = colouredPixelsInData(log_image, log_layout);
    qInfo("in-plane curve pixels: linear %lld, log %lld", static_cast<long long>(linear),
          static_cast<long long>(log_pixels));
    // The same curves on another scale: of the same order of ink.
    QVERIFY2(log_pixels > linear / 3, qPrintable(QStringLiteral("%1 of %2").arg(log_pixels).arg(linear)));
    QVERIFY2(log_layout.title.contains(QStringLiteral("<= 0 are not drawn")), qPrintable(log_layout.title));

    PlotsDock dock;
    dock.resize(1000, 500);
    dock.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dock));
    dock.setBrdf(m_pearl);
    QTRY_VERIFY_WITH_TIMEOUT(dock.brdf() != nullptr && !dock.computing(), kWaitMs);
    auto* log = dock.findChild<QCheckBox*>(QStringLiteral("plots_log"));
    QVERIFY(log != nullptr);
    log->setChecked(true);
    dock.tabs()->setCurrentWidget(dock.paintSpectra());
    QVERIFY(QTest::qWaitForWindowExposed(dock.paintSpectra()));
    const QImage spectra = dock.paintSpectra()->renderImage();
    QVERIFY(spectra.save(screenshotDir() + "/plots_paint_spectra_log.png"));
    const PlotWidget::ChartLayout layout = dock.paintSpectra()->chartLayout();
    QVERIFY(layout.left_log);
    QVERIFY(colouredPixelsInData(spectra, layout) > 500);
}

// Issue 27 item 12: no legend over the curves, with or without a comparison.
void PlotsTest::legendsAreOutsideTheData() {
    m_inplane->setComparison(*m_fewer, QStringLiteral("full model (Monte Carlo, 123456 paths, 20.0 s)"));
    m_ab->setComparison(*m_fewer, QStringLiteral("half the flakes"));
    const std::vector<std::pair<PlotWidget*, const char*>> plots{
        {m_inplane.get(), "plots_inplane_legend"},
        {m_paint_spectra.get(), "plots_paint_legend"},
        {m_ingredient_spectra.get(), "plots_ingredient_legend"},
        {m_ab.get(), "plots_ab_legend"}};
    for (const auto& [plot, name] : plots) {
        QVERIFY(plot->renderImage().save(screenshotDir() + "/" + name + ".png"));
        const PlotWidget::ChartLayout l = plot->chartLayout();
        QVERIFY2(!l.legend.isEmpty() && !l.data.isEmpty(), name);
        QVERIFY2(!l.legend.intersects(l.data),
                 qPrintable(QStringLiteral("%1: legend %2,%3 %4x%5 over the data %6,%7 %8x%9")
                                .arg(name)
                                .arg(l.legend.x())
                                .arg(l.legend.y())
                                .arg(l.legend.width())
                                .arg(l.legend.height())
                                .arg(l.data.x())
                                .arg(l.data.y())
                                .arg(l.data.width())
                                .arg(l.data.height())));
        QVERIFY2(l.scene.contains(l.legend), qPrintable(QStringLiteral("%1: legend %2,%3 %4x%5 in %6x%7")
                                                            .arg(name)
                                                            .arg(l.legend.x())
                                                            .arg(l.legend.y())
                                                            .arg(l.legend.width())
                                                            .arg(l.legend.height())
                                                            .arg(l.scene.width())
                                                            .arg(l.scene.height())));
    }
    // The comparison is one legend line, not one per incidence.
    const PlotWidget::ChartLayout inplane = m_inplane->chartLayout();
    QCOMPARE(inplane.legend_labels.size(), qsizetype{5 + 3 + 1});
    QVERIFY(inplane.legend_labels.contains(QStringLiteral("dashed: full model")));
    m_inplane->clearComparison();
    m_ab->clearComparison();
}

void PlotsTest::abChartHasEqualScalesAndSeparateLabels() {
    for (const QSize size : {QSize(720, 480), QSize(500, 640)}) {
        m_ab->resize(size);
        QTRY_COMPARE_WITH_TIMEOUT(m_ab->size(), size, kWaitMs);
        m_ab->renderImage();
        const PlotWidget::ChartLayout l = m_ab->chartLayout();
        const double a_per_px = (l.bottom_max - l.bottom_min) / l.data.width();
        const double b_per_px = (l.left_max - l.left_min) / l.data.height();
        // 1 %: a pixel of rounding in a box of a few hundred.
        QVERIFY2(std::abs(a_per_px / b_per_px - 1.0) < 0.01,
                 qPrintable(QStringLiteral("a* %1 / px, b* %2 / px at %3x%4")
                                .arg(a_per_px)
                                .arg(b_per_px)
                                .arg(size.width())
                                .arg(size.height())));
        QVERIFY(!l.legend.intersects(l.data) && l.scene.contains(l.legend));
        const std::vector<QRectF> labels = m_ab->labelRects();
        QCOMPARE(labels.size(), std::size_t{6});
        for (std::size_t i = 0; i < labels.size(); ++i)
            for (std::size_t j = i + 1; j < labels.size(); ++j)
                QVERIFY2(!labels[i].intersects(labels[j]),
                         qPrintable(QStringLiteral("labels %1 and %2 overlap").arg(i).arg(j)));
    }
    QVERIFY(m_ab->renderImage().save(screenshotDir() + "/plots_ab_square.png"));
    m_ab->resize(720, 480);
}

// The value axis' title is never longer than its axis (Ingredient spectra's
// "Absorption and scattering coefficients (1/µm)" was cut off), and the
// ingredient browser's spectrum chart labels its value axis.
void PlotsTest::axisTitlesFit() {
    // As tall as the plot is in the Plots dock at 1366x768 (~360 pixels).
    m_ingredient_spectra->resize(720, 360);
    QTRY_COMPARE_WITH_TIMEOUT(m_ingredient_spectra->height(), 360, kWaitMs);
    for (const std::string& quantity : m_ingredient_spectra->quantities()) {
        m_ingredient_spectra->setQuantity(quantity);
        m_ingredient_spectra->renderImage();
        const PlotWidget::ChartLayout l = m_ingredient_spectra->chartLayout();
        qInfo("%s: axis title %.0f px, axis %.0f px", quantity.c_str(), l.left_title_px, l.data.height());
        QVERIFY2(l.left_title_px > 0.0 && l.left_title_px <= l.data.height(),
                 qPrintable(QStringLiteral("%1: title %2 px, axis %3 px")
                                .arg(l.left_title)
                                .arg(l.left_title_px)
                                .arg(l.data.height())));
    }
    m_ingredient_spectra->setQuantity(m_ingredient_spectra->quantities().front());
    m_ingredient_spectra->resize(720, 480);
    SpectrumChart chart;
    chart.resize(chart.sizeHint());
    chart.show();
    QVERIFY(QTest::qWaitForWindowExposed(&chart));
    chart.setSpectrum(QStringLiteral("sigma_a"), QString::fromUtf8("1/\u00b5m"), {400.0, 550.0, 700.0},
                      {0.5, 2.0, 1.0});
    const QImage image = chart.grab().toImage();
    QVERIFY(image.save(screenshotDir() + "/ingredient_spectrum_chart.png"));
    QVERIFY(chart.sizeHint().height() >= 240);
    QVERIFY(!chart.valueAxisTitleRect().isEmpty());
    QVERIFY(chart.rect().contains(chart.valueAxisTitleRect()));
}

// Issue 27 item 10: a comparison handed to the dock is on the paint spectra too.
void PlotsTest::dockComparisonIsOnThePaintSpectraToo() {
    PlotsDock dock;
    dock.resize(1000, 500);
    dock.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dock));
    dock.setBrdf(m_pearl);
    dock.setComparison(m_fewer, QStringLiteral("half the flakes"));
    QTRY_VERIFY_WITH_TIMEOUT(!dock.computing() && dock.inplanePlot()->hasComparison(), kWaitMs);
    QCOMPARE(dock.paintSpectra()->comparisonSpectra().size(), std::size_t{6});
    // The status line's text (times, a full model's label) does not widen the
    // dock past a laptop screen (it made the Plots dock ~1500 pixels wide).
    QVERIFY(!dock.status()->text().isEmpty());
    QVERIFY2(dock.minimumSizeHint().width() <= 1024,
             qPrintable(QStringLiteral("%1 pixels").arg(dock.minimumSizeHint().width())));
    const QString path = m_dir.filePath("spectra_cmp.csv");
    QVERIFY(dock.paintSpectra()->exportCsv(path));
    const Csv csv = readCsv(path);
    qsizetype compared = 0;
    for (const QStringList& row : csv.rows)
        compared += row[0].startsWith(QStringLiteral("half the flakes: 45as"));
    QVERIFY(compared > 6);
    dock.clearComparison();
    QVERIFY(!dock.paintSpectra()->hasComparison());
}

void PlotsTest::mainWindowPlotsDockFollowsTheRecipe() {
    paintlab::test::isolateUserFolders(m_dir.path());
    WorkstationOptions options;
    options.database = m_dir.filePath("lab.db").toStdString();
    options.open_scene = false;  // the BRDF alone: no scene to trace
    MainWindow window(options);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    PlotsDock* dock = window.plotsDock();
    QVERIFY(dock != nullptr);
    QCOMPARE(dock->plots().size(), std::size_t{5});
    QVERIFY(window.selectRecipe(kPearl));
    QTRY_VERIFY_WITH_TIMEOUT(dock->brdf() != nullptr && window.scheduler()->idle() && !dock->computing(),
                             kWaitMs);
    QVERIFY(!dock->ingredientSpectra()->spectra().empty());
    // The dock's in-plane data is that of the BRDF the scheduler delivered.
    const QString path = m_dir.filePath("dock_inplane.csv");
    dock->tabs()->setCurrentWidget(dock->inplanePlot());
    QVERIFY(dock->exportCurrentCsv(path));
    verifyInplaneCsv(path, *dock->brdf(), QStringLiteral("current"));
    qInfo("Plots dock (standard preset, %zu bands): data %.1f ms on the worker, drawn %.1f ms on the GUI "
          "thread",
          dock->brdf()->wavelengthsNm().size(), dock->lastComputeMs(), dock->lastUpdateMs());
    QElapsedTimer timer;
    timer.start();
    window.plot()->setBrdf(*dock->brdf());  // the central plot computes on the GUI thread
    qInfo("central in-plane plot (45 deg alone): %.1f ms on the GUI thread",
          static_cast<double>(timer.nsecsElapsed()) * 1e-6);
    for (int tab = 0; tab < dock->tabs()->count(); ++tab) {
        dock->tabs()->setCurrentIndex(tab);
        QVERIFY(dock->currentPlot() != nullptr);
        QVERIFY(QTest::qWaitForWindowExposed(dock->currentPlot()));
        const QImage image = dock->currentPlot()->renderImage();
        QVERIFY(pixelStats(image).colours > 20);
    }
    PlotRenderThread::instance().settle();
    QVERIFY(window.grab().save(screenshotDir() + "/plots_main_window.png"));
    // Floating the dock and docking it again moves its plots to another
    // top-level window: they keep drawing, in as many colours, and the widget
    // shows what was drawn (its own paint, not the render thread's image).
    for (const bool floating : {true, false}) {
        dock->setFloating(floating);
        QVERIFY(QTest::qWaitForWindowExposed(dock->currentPlot()));
        QTRY_VERIFY_WITH_TIMEOUT(pixelStats(dock->currentPlot()->renderImage()).colours > 20, kWaitMs);
        PlotRenderThread::instance().settle();
        QVERIFY(pixelStats(dock->currentPlot()->grab().toImage()).colours > 20);
    }
    // Pinning, then an edit: the comparison stays, the current series follows.
    dock->pinCurrentAsComparison();
    QTRY_VERIFY_WITH_TIMEOUT(!dock->computing(), kWaitMs);
    QVERIFY(dock->inplanePlot()->hasComparison() && dock->abChart()->hasComparison());
    const auto pinned = dock->brdf();
    window.document()->load(fewerFlakes(pearlRecipe()), QStringLiteral("fewer flakes"), 0);
    QTRY_VERIFY_WITH_TIMEOUT(dock->brdf() != pinned && window.scheduler()->idle() && !dock->computing(),
                             kWaitMs);
    QVERIFY(dock->abChart()->report().colours[1].lab.L !=
            dock->abChart()->comparisonReport().colours[1].lab.L);
    // The incidence chooser: the lobe is recomputed for the new light.
    auto* theta_i = dock->findChild<QDoubleSpinBox*>(QStringLiteral("lobe_theta_i"));
    QVERIFY(theta_i != nullptr);
    QSignalSpy updated(dock, &PlotsDock::updated);
    theta_i->setValue(30.0);
    QTRY_VERIFY_WITH_TIMEOUT(updated.count() >= 1 && !dock->computing(), kWaitMs);
    QCOMPARE(dock->lobePlot()->grid().theta_i_deg, 30.0);
    dock->clearComparison();
    QVERIFY(!dock->inplanePlot()->hasComparison());
}

void PlotsTest::cleanupTestCase() {
    m_inplane.reset();
    m_lobe.reset();
    m_paint_spectra.reset();
    m_ingredient_spectra.reset();
    m_ab.reset();
}

int main(int argc, char** argv) {
    return paintlab::test::runGuiTest<PlotsTest>(argc, argv, "PaintLab-test-plots");
}

#include "test_plots.moc"
