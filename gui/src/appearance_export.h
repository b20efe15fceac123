#pragma once
// File > Export appearance...: a recipe's appearance written by one of the
// plugin registry's AppearanceExporters (the BRDF table, MERL .binary, glTF,
// MaterialX and whatever a plugin adds) off the GUI thread: the fast model at
// a preset (about 1 s at standard), then the exporter, on a thread of its
// own, with progress on the GUI thread and cancel at every progress step.
// An exporter with long work of its own reports it through
// ExportOptions::progress (MERL's 1.46 million bins, about a minute,
// docs/PERFORMANCE.md) and stops there when cancelled; the others write in
// a second or two. One export at a time; destroying the object cancels and
// waits for the thread.

#include "background_job.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/plugins/plugin.h"

#include <QString>

#include <filesystem>

namespace paintlab::gui {

class AppearanceExport : public BackgroundJob {
    Q_OBJECT
public:
    explicit AppearanceExport(QObject* parent = nullptr) : BackgroundJob(parent) {}

    // Starts the export; false if one is running. `exporter` comes from
    // plugins::Registry::global() (its plugins are never unloaded).
    // options.settings_json is filled in from the fast model's settings.
    bool start(Recipe recipe, Preset preset, const plugins::AppearanceExporter* exporter,
               std::filesystem::path file, plugins::ExportOptions options);
    // cancel(), running(), wait(): BackgroundJob's.

signals:
    void progressed(double fraction);       // the fast model's
    void writing();                         // the fast model is done; the exporter writes
    void writeProgressed(double fraction);  // the exporter's, if it reports any
    // "Wrote FILE (format, bands, fast model seconds)", then the exporter's
    // report (an approximation's ΔE00) if it gives one.
    void finished(const QString& message);
    // The error's text: it names the file (or the recipe's field).
    void failed(const QString& message);
    void cancelled();
};

}  // namespace paintlab::gui
