// A recipe's appearance exported on its own thread (appearance_export.h).

#include "appearance_export.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_validation.h"
#include "paintlab/plugins/exchange.h"

#include <atomic>
#include <exception>
#include <functional>
#include <utility>

namespace paintlab::gui {

bool AppearanceExport::start(Recipe recipe, Preset preset, const plugins::AppearanceExporter* exporter,
                             std::filesystem::path file, plugins::ExportOptions options) {
    if (exporter == nullptr) return false;
    return startJob([this, recipe = std::move(recipe), preset, exporter, file = std::move(file),
                     options = std::move(options)](const std::atomic<bool>& cancel) mutable {
        // Progress thinned to 1 % steps: a bar needs no more.
        int last = -1;
        const ProgressCallback progress = [this, &cancel, &last](double fraction) {
            const int percent = static_cast<int>(100.0 * fraction);
            if (percent != last) {
                last = percent;
                post([this, fraction]() { emit progressed(fraction); });
            }
            return !cancel.load();
        };
        // The exporter may report from several threads at once.
        std::atomic<int> last_written{-1};
        options.progress = [this, &cancel, &last_written](double fraction) {
            const int percent = static_cast<int>(100.0 * fraction);
            if (last_written.exchange(percent) != percent)
                post([this, fraction]() { emit writeProgressed(fraction); });
            return !cancel.load();
        };
        std::function<void()> deliver;
        try {
            validateRecipe(recipe, options.recipe_path);
            const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(preset), progress);
            options.settings_json = plugins::fastModelSettingsJson(brdf, presetName(preset));
            if (cancel.load()) throw Error("cancelled");
            post([this]() { emit writing(); });
            const std::string report = exporter->write(recipe, brdf, file, options);
            QString message = tr("Wrote %1 (%2, %3 bands, fast model %4 s)")
                                  // The file name alone: the folder is the one just chosen, and the report
                                  // after it must fit.
                                  .arg(QString::fromStdString(file.filename().string()),
                                       QString::fromStdString(exporter->format().id))
                                  .arg(brdf.wavelengthsNm().size())
                                  .arg(brdf.computeSeconds(), 0, 'f', 2);
            if (!report.empty()) message += QStringLiteral(". ") + QString::fromStdString(report);
            deliver = [this, message]() { emit finished(message); };
        } catch (const std::exception& e) {
            if (cancel.load())
                deliver = [this]() { emit cancelled(); };
            else
                deliver = [this, message = QString::fromUtf8(e.what())]() { emit failed(message); };
        }
        return deliver;
    });
}

}  // namespace paintlab::gui
