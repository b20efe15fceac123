#pragma once
// The Match dock's split view (issue 28, part 3): a sphere painted half with
// a BRDF measurement (left, "measured") and half with a recipe (right: the
// fitted recipe, "fitted", or the recipe being edited before a fit,
// "recipe"), split_sphere.h shading them. Everything slow runs on a worker (latest_job.h): reading
// the samples, judging their density, the recipe's fast model and the
// shading; a newer request or cancel() stops a running one between rows (or
// in the fast model's progress), and the GUI thread only shows the image.
// A measurement too sparse to shade with (measured::density) shows why
// instead of a sphere.

#include "latest_job.h"

#include "paintlab/database/measurements.h"
#include "paintlab/engine/recipe.h"

#include <QImage>
#include <QString>
#include <QWidget>

#include <atomic>
#include <memory>

class QLabel;

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

class SplitSphereView : public QWidget {
    Q_OBJECT
public:
    // The sphere's size in pixels (rendered; shown scaled to the widget).
    static constexpr int kSpherePx = 160;

    explicit SplitSphereView(QWidget* parent = nullptr);
    ~SplitSphereView() override;
    SplitSphereView(const SplitSphereView&) = delete;
    SplitSphereView& operator=(const SplitSphereView&) = delete;
    SplitSphereView(SplitSphereView&&) = delete;
    SplitSphereView& operator=(SplitSphereView&&) = delete;

    // Shades `measurement` (left) against `recipe` (right, labelled
    // right_label) on the worker; replaces a running request.
    void shade(const std::shared_ptr<const db::Measurement>& measurement, const Recipe& recipe,
               const QString& right_label);
    // No sphere: the message instead (and a running request stopped).
    void showMessage(const QString& message);
    void cancel();
    bool busy() const { return m_job.busy(); }

    // What is shown (tests): the sphere's image (null with a message), the
    // message, the right half's label.
    const QImage& image() const { return m_image; }
    bool showsSpheres() const { return !m_image.isNull(); }
    QString message() const;
    const QString& rightLabel() const { return m_right_label; }
    // The exposure both halves share (EV) and the seconds of the last shading.
    double exposureEv() const { return m_exposure_ev; }
    double seconds() const { return m_seconds; }

signals:
    // The sphere or the message is shown for the newest request.
    void shown();
    // The recipe's fast model of the newest request (standard preset), for
    // the plots' fitted curve; also for a measurement too sparse to shade.
    void recipeBrdfReady(std::shared_ptr<const paintlab::LayeredBrdf> brdf, const QString& right_label);

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    void setMessage(const QString& message);

    LatestJob m_job;
    std::shared_ptr<std::atomic<bool>> m_cancel;  // of the newest request
    quint64 m_generation = 0;
    // The newest request's inputs: the same again is not shaded again.
    std::shared_ptr<const db::Measurement> m_measurement;
    std::unique_ptr<Recipe> m_recipe;
    QString m_requested_label;
    QLabel* m_message = nullptr;
    QImage m_image;
    QString m_right_label;
    double m_exposure_ev = 0.0;
    double m_seconds = 0.0;
};

}  // namespace paintlab::gui
