// The Match dock's split view (split_sphere_view.h).

#include "split_sphere_view.h"

#include "split_sphere.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/measured/scattered_brdf.h"
#include "paintlab/raymaps/display_image.h"

#include <QLabel>
#include <QPainter>
#include <QVBoxLayout>

#include <chrono>

namespace paintlab::gui {

SplitSphereView::SplitSphereView(QWidget* parent) : QWidget(parent) {
    setObjectName("match_split_view");
    setMinimumSize(120, 120);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    m_message = new QLabel;
    m_message->setObjectName("match_split_message");
    m_message->setWordWrap(true);
    m_message->setAlignment(Qt::AlignCenter);
    layout->addWidget(m_message);
    setToolTip(
        tr("Left: the measured BRDF (its samples interpolated in half/difference angles); right: the "
           "recipe's fast model. One exposure; a key light from the upper left, a fill from the right, "
           "a dim light from the viewer."));
    connect(&m_job, &LatestJob::failed, this, [this](const QString& message) {
        if (message == QStringLiteral("cancelled")) return;
        m_measurement.reset();  // a retry shades again
        setMessage(tr("Split view not shown: %1").arg(message));
        emit shown();
    });
    setMessage(tr("Choose a BRDF measurement for the split view of measured against fitted."));
}

SplitSphereView::~SplitSphereView() {
    if (m_cancel) *m_cancel = true;  // the job's destructor then waits briefly
}

QString SplitSphereView::message() const { return m_message->isVisible() ? m_message->text() : QString(); }

void SplitSphereView::setMessage(const QString& message) {
    m_image = {};
    m_message->setText(message);
    m_message->show();
    update();
}

void SplitSphereView::cancel() {
    if (m_cancel) *m_cancel = true;
    ++m_generation;
    m_measurement.reset();
    m_recipe.reset();
}

void SplitSphereView::showMessage(const QString& message) {
    cancel();
    setMessage(message);
}

void SplitSphereView::shade(const std::shared_ptr<const db::Measurement>& measurement, const Recipe& recipe,
                            const QString& right_label) {
    if (m_measurement && m_recipe && *m_measurement == *measurement && *m_recipe == recipe &&
        m_requested_label == right_label)
        return;  // shown or being shaded
    cancel();
    m_measurement = measurement;
    m_recipe = std::make_unique<Recipe>(recipe);
    m_requested_label = right_label;
    m_cancel = std::make_shared<std::atomic<bool>>(false);
    const quint64 generation = m_generation;
    setMessage(tr("Shading the split view..."));
    m_job.run([this, measurement, recipe, right_label, generation, cancel = m_cancel]() -> LatestJob::Apply {
        const auto start = std::chrono::steady_clock::now();
        const auto alive = [cancel]() { return !cancel->load(); };
        const measured::ScatteredBrdf left(linearSrgbSamples(*measurement), 3,
                                           "measurement '" + measurement->name + "'");
        const measured::Density density = measured::density(left, splitSphereQueries(kSpherePx));
        auto right = std::make_shared<const LayeredBrdf>(computeLayeredBrdf(
            recipe, presetSettings(Preset::Standard), [alive](double) { return alive(); }));
        if (!density.dense) {
            const QString reason = QString::fromStdString(density.reason);
            return [this, generation, right, right_label, reason]() {
                if (generation != m_generation) return;
                setMessage(tr("This measurement is too sparse to shade a sphere with: %1.").arg(reason));
                emit recipeBrdfReady(right, right_label);
                emit shown();
            };
        }
        const raymaps::RgbImage linear = renderSplitSphere(rgbBrdf(left), rgbBrdf(*right), kSpherePx, alive);
        const double ev = splitSphereExposureEv(linear);
        const std::vector<std::uint8_t> bytes = raymaps::toDisplayRgb8(linear, ev);
        QImage image(kSpherePx, kSpherePx, QImage::Format_RGB888);
        for (int y = 0; y < kSpherePx; ++y)
            std::copy_n(bytes.data() + 3 * static_cast<std::size_t>(y) * kSpherePx, 3 * kSpherePx,
                        image.scanLine(y));
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return [this, generation, image, ev, seconds, right, right_label]() {
            if (generation != m_generation) return;
            m_message->hide();
            m_image = image;
            m_exposure_ev = ev;
            m_seconds = seconds;
            m_right_label = right_label;
            update();
            emit recipeBrdfReady(right, right_label);
            emit shown();
        };
    });
}

void SplitSphereView::paintEvent(QPaintEvent* /*event*/) {
    if (m_image.isNull()) return;
    QPainter painter(this);
    painter.fillRect(rect(), QColor(40, 40, 40));
    // The sphere as large as fits, labels above it.
    const int label_h = fontMetrics().height() + 4;
    const int side = std::max(16, std::min(width(), height() - label_h));
    const QRect target((width() - side) / 2, label_h + (height() - label_h - side) / 2, side, side);
    painter.setRenderHint(QPainter::SmoothPixmapTransform);
    painter.drawImage(target, m_image);
    painter.setPen(QPen(QColor(255, 255, 255), 1.5));
    const int middle = target.left() + side / 2;
    painter.drawLine(middle, target.top(), middle, target.bottom());
    painter.setPen(QColor(230, 230, 230));
    // Each label in its half, elided if the view is narrow.
    const QRect labels(target.left(), target.top() - label_h, side, label_h);
    const int half = side / 2 - 4;
    painter.drawText(labels.adjusted(2, 0, -side / 2, 0), Qt::AlignLeft | Qt::AlignVCenter,
                     fontMetrics().elidedText(tr("measured"), Qt::ElideRight, half));
    painter.drawText(labels.adjusted(side / 2, 0, -2, 0), Qt::AlignRight | Qt::AlignVCenter,
                     fontMetrics().elidedText(m_right_label, Qt::ElideRight, half));
}

}  // namespace paintlab::gui
