#pragma once
// Screenshots of the workstation's window and docks against baselines
// (issue 8): each grab is saved as <build dir>/screenshots/<name>.png for the
// test log, converted to grey (Rec. 601 luma, what SSIM was defined on) and
// compared by mean SSIM (tests/support/ssim.h) with tests/gui/baselines/<name>.png.
// PAINTLAB_UPDATE_BASELINES=1 in the environment writes the baselines
// instead (after a deliberate change of the GUI; review them before committing).

#include "plot_render_thread.h"
#include "ssim.h"

#include <QDir>
#include <QImage>
#include <QString>
#include <QWidget>

#include <cmath>
#include <stdexcept>

namespace paintlab::test {

inline GreyImage greyOf(const QImage& image) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    GreyImage out{rgb.width(), rgb.height(), {}};
    out.value.reserve(static_cast<std::size_t>(rgb.width()) * static_cast<std::size_t>(rgb.height()));
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QRgb p = rgb.pixel(x, y);
            out.value.push_back(0.299 * qRed(p) + 0.587 * qGreen(p) + 0.114 * qBlue(p));
        }
    return out;
}

struct BaselineComparison {
    bool ok = false;
    double ssim = 0.0;
    QString message;
};

// Grabs `widget`, with the plots' latest drawings (the plot render thread's
// queue is drained first), and compares it with its baseline; ok if the mean
// SSIM is at least `threshold`.
inline BaselineComparison compareWithBaseline(QWidget& widget, const QString& name, double threshold) {
    paintlab::gui::PlotRenderThread::instance().settle();
    const QImage shot = widget.grab().toImage();
    QDir().mkpath(QStringLiteral("screenshots"));
    const QString shot_file = QStringLiteral("screenshots/%1.png").arg(name);
    shot.save(shot_file);
    const QString baseline_file = QStringLiteral(PAINTLAB_GUI_BASELINE_DIR "/%1.png").arg(name);
    if (qEnvironmentVariableIntValue("PAINTLAB_UPDATE_BASELINES") == 1) {
        const bool saved = shot.save(baseline_file);
        return {saved, 1.0, saved ? "baseline written: " + baseline_file : "cannot write " + baseline_file};
    }
    const QImage baseline(baseline_file);
    if (baseline.isNull())
        return {false, 0.0, "no baseline " + baseline_file + " (run with PAINTLAB_UPDATE_BASELINES=1)"};
    if (baseline.size() != shot.size())
        return {false, 0.0,
                QStringLiteral("%1: %2 x %3, baseline %4 x %5")
                    .arg(shot_file)
                    .arg(shot.width())
                    .arg(shot.height())
                    .arg(baseline.width())
                    .arg(baseline.height())};
    const double ssim = meanSsim(greyOf(shot), greyOf(baseline));
    return {ssim >= threshold, ssim,
            QStringLiteral("%1: mean SSIM %2 against %3 (threshold %4)")
                .arg(shot_file)
                .arg(ssim, 0, 'f', 4)
                .arg(baseline_file)
                .arg(threshold)};
}

}  // namespace paintlab::test
