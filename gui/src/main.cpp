// paintlab: the workstation. Opens the user's database (created from the demo
// data on first use) and the demo scene, whose ray map is traced once and
// cached; every recipe edit re-shades only the paint.

#include "file_output.h"
#include "main_window.h"
#include "plot_render_thread.h"
#include "plots_dock.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QTimer>

#include "render_dock.h"

#include <cstdio>
#include <cstdlib>

namespace {

// Without a display Qt aborts with a cryptic message; say what to do instead.
bool displayAvailable() {
    const auto set = [](const char* name) {
        const char* v = std::getenv(name);  // NOLINT(concurrency-mt-unsafe): before any thread starts
        return v != nullptr && *v != '\0';
    };
    return set("QT_QPA_PLATFORM") || set("DISPLAY") || set("WAYLAND_DISPLAY");
}

}  // namespace

int main(int argc, char** argv) {
    if (!displayAvailable()) {
        std::fputs(
            "paintlab: no display (neither DISPLAY nor WAYLAND_DISPLAY is set).\n"
            "Run it in a virtual X server: xvfb-run -a paintlab (add --screenshot FILE.png to save\n"
            "the window once it shows its first image); Qt's offscreen platform (QT_QPA_PLATFORM=offscreen)\n"
            "has no OpenGL for the plots. paintlab-cli offers every computation without a display.\n",
            stderr);
        return 2;
    }
    // VTK's OpenGL2 backend needs a 3.2 core profile, set before the application
    // exists (shared/notes/debian12-stack.md, trap 4).
    QSurfaceFormat format;
    format.setVersion(3, 2);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(24);
    format.setStencilBufferSize(8);
    QSurfaceFormat::setDefaultFormat(format);

    QApplication app(argc, argv);
    QApplication::setOrganizationName("PaintLab");
    QApplication::setApplicationName("PaintLab");
    QApplication::setApplicationVersion("0.1.0");

    QCommandLineParser parser;
    parser.setApplicationDescription("PaintLab workstation: ingredients, recipes, BRDF plots, relit scene.");
    parser.addHelpOption();
    parser.addVersionOption();
    const QCommandLineOption db(QStringLiteral("db"),
                                "Database file (default: the user's, created from the demo).", "FILE");
    const QCommandLineOption scene(QStringLiteral("scene"), "Scene file (default: the bundled demo scene).",
                                   "FILE");
    const QCommandLineOption raymap(QStringLiteral("raymap"),
                                    "Ray map of the scene (default: traced once and cached).", "FILE");
    const QCommandLineOption no_scene(QStringLiteral("no-scene"), "Open no scene (plots only).");
    const QCommandLineOption recipe(QStringLiteral("recipe"), "Recipe of the database to select at start.",
                                    "NAME");
    const QCommandLineOption screenshot(
        QStringLiteral("screenshot"),
        "Once the first full-quality image is shown, save the window to FILE (PNG) and quit.", "FILE");
    parser.addOptions({db, scene, raymap, no_scene, recipe, screenshot});
    parser.process(app);

    paintlab::gui::WorkstationOptions options;
    options.database = parser.value(db).toStdString();
    options.scene = parser.value(scene).toStdString();
    options.raymap = parser.value(raymap).toStdString();
    options.open_scene = !parser.isSet(no_scene);
    paintlab::gui::MainWindow window(options);
    window.show();
    // Unsaved edits a crash or a kill left behind come first (restore or
    // discard). A scripted screenshot neither asks nor touches them.
    if (parser.isSet(screenshot)) window.recoveryDraft()->setDatabase({});
    const bool restored = !parser.isSet(screenshot) && window.offerRecoveredDraft();
    if (parser.isSet(recipe) && !restored) window.selectRecipe(parser.value(recipe));
    if (parser.isSet(screenshot)) {
        // The shot waits for the recipe's image (traced and relit) when one is
        // selected, then for the plots' data (their worker) and their latest
        // drawings (plot render thread). Without a recipe (a fresh database
        // shows the first-start hint) there is no image to wait for.
        const QString file = parser.value(screenshot);
        auto* poll = new QTimer(&window);
        QObject::connect(poll, &QTimer::timeout, &window, [&window, file, poll]() {
            if (!window.scheduler()->idle()) return;
            if (window.document()->hasRecipe() && window.renderDock()->image().isNull()) return;
            if (window.plotsDock()->computing()) return;
            poll->stop();
            paintlab::gui::PlotRenderThread::instance().settle();
            const int code = paintlab::gui::saveImageAtomically(window.grab().toImage(), file) ? 0 : 1;
            if (code != 0) std::fprintf(stderr, "paintlab: cannot write %s\n", qPrintable(file));
            QApplication::exit(code);
        });
        poll->start(50);
    }
    return QApplication::exec();
}
