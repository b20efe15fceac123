// `raymap build`, `relight` and `render`: ray maps from the command line
// (docs/RAYMAPS.md). Options are a public contract (issue 6): extend, never rename.

#include "commands.h"
#include "helper_commands.h"
#include "sparkle_option.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/paint_proxy.h"
#include "paintlab/raymaps/planned_relight.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/reference.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace paintlab::cli {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct BuildOptions {
    std::string scene;
    std::string out;
    raymaps::RayMapSettings settings;
    int width = 0;  // 0: the scene's camera
    int height = 0;
};

struct RelightOptions {
    std::string map;
    std::string recipe;
    std::string preset = "standard";
    std::string out;
    double exposure_ev = 0.0;
    int repeat = 1;
    SparkleOption sparkle;
};

void addBuildOptions(CLI::App* command, BuildOptions& o) {
    command->add_option("--aa", o.settings.aa_samples, "Camera samples per pixel")->capture_default_str();
    command
        ->add_option("--bake-paths", o.settings.bake_paths, "Paths per camera sample on non-paint surfaces")
        ->capture_default_str();
    command->add_option("--light-rays", o.settings.light_rays, "Hemisphere rays per paint pixel")
        ->capture_default_str();
    command->add_option("--cells", o.settings.cells, "J: cells in cos(theta_i) of the light moments")
        ->capture_default_str();
    command->add_option("--orders", o.settings.orders, "M_L: azimuthal orders of the light moments")
        ->capture_default_str();
    command->add_option("--seed", o.settings.seed, "Random seed")->capture_default_str();
    command
        ->add_option("--passes", o.settings.passes,
                     "Passes averaged (seeds seed, seed + 1, ...): the noise falls as 1/sqrt(passes)")
        ->capture_default_str();
    command
        ->add_option("--env-lights", o.settings.env_lights,
                     "K_env: HDR hotspots made explicit lights (at most)")
        ->capture_default_str();
    command->add_option("--width", o.width, "Image width (default: the scene camera's)");
    command->add_option("--height", o.height, "Image height (default: the scene camera's)");
}

void addRelightOptions(CLI::App* command, RelightOptions& o) {
    command->add_option("--recipe", o.recipe, "Recipe JSON file")->required();
    command->add_option("--preset", o.preset, "Fast-model preset: preview, standard or reference")
        ->capture_default_str();
    command->add_option("--out", o.out, "Output image: .exr (linear) or .png (tone mapped)")->required();
    command->add_option("--exposure", o.exposure_ev, "Exposure in EV (x 2^EV)")->capture_default_str();
}

raymaps::RayMapProgress terminalProgress(const char* what) {
    if (isatty(STDERR_FILENO) == 0) return {};
    return [what](double fraction) {
        std::fprintf(stderr, "\r%s: %3.0f%%", what, 100.0 * fraction);
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        return true;
    };
}

// --width/--height override the scene camera's resolution (both or neither).
void applySize(raymaps::Scene& scene, int width, int height) {
    if (width == 0 && height == 0) return;
    if (width < 1 || width > 16384 || height < 1 || height > 16384)
        throw InputError("<argument>", "--width/--height", "give both, each in [1, 16384]");
    scene.camera.width = width;
    scene.camera.height = height;
}

void build(const BuildOptions& o, const std::filesystem::path& out) {
    raymaps::Scene scene = raymaps::loadSceneFile(o.scene);
    applySize(scene, o.width, o.height);
    const raymaps::RayMapHeader h = raymaps::buildRayMap(scene, o.settings, out, terminalProgress("ray map"));
    const auto record = raymaps::recordBytes(h.cells, h.orders, static_cast<int>(h.lights.size()));
    std::printf("ray map %s: %d x %d, %llu paint pixels, %zu bytes per paint record, %llu bytes on disk\n",
                out.string().c_str(), h.width, h.height, static_cast<unsigned long long>(h.paint_pixels),
                record, static_cast<unsigned long long>(std::filesystem::file_size(out)));
    std::printf("precompute: %.2f s, %llu rays, %.3g rays/s\n", h.seconds,
                static_cast<unsigned long long>(h.rays),
                h.seconds > 0.0 ? static_cast<double>(h.rays) / h.seconds : 0.0);
}

// Before any work: a wrong image type is found in a second, not after the precompute.
void checkImagePath(const std::string& out) {
    std::string ext = std::filesystem::path(out).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr" && ext != ".png")
        throw InputError("<argument>", "--out", out + ": the image must be .exr (linear) or .png");
}

int relightMap(const RelightOptions& o, const std::filesystem::path& map_path) {
    checkImagePath(o.out);
    if (o.repeat < 1 || o.repeat > 1000) throw InputError("<argument>", "--repeat", "must be in [1, 1000]");
    const Preset preset = presetFromName(o.preset);
    auto start = Clock::now();
    const auto map = raymaps::RayMap::open(map_path);
    map->loadAll();
    const double load_s = secondsSince(start);
    // Decoded once per map (geometry only); each recipe change then costs
    // the fast model, the tables and the kernel below.
    const raymaps::RelightInput input(*map);
    start = Clock::now();
    const Recipe recipe = loadRecipeFile(o.recipe);
    // The effect plan (--plan, --sparkle plan): from the map's lights and
    // footprints; --plan runs the fast model at its settings.
    std::optional<EffectPlan> effect_plan;
    double plan_s = 0.0;
    if (o.sparkle.needsPlan()) {
        effect_plan = planForMap(o.sparkle, *map, recipe, preset);
        plan_s = secondsSince(start);
        start = Clock::now();
    }
    const FastModelSettings settings =
        o.sparkle.plan ? raymaps::plannedSettings(*effect_plan) : presetSettings(preset);
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, settings);
    const double brdf_s = secondsSince(start);
    start = Clock::now();
    const raymaps::RelightTables tables(brdf, map->header().cells, map->header().orders);
    const double tables_s = secondsSince(start);
    raymaps::RgbImage image;
    double best_s = 1e30;
    // Processor time too (all threads): on a machine shared with other jobs
    // the wall time says little, CPU time / cores is the time on idle cores.
    const std::clock_t cpu_start = std::clock();
    for (int i = 0; i < o.repeat; ++i) {
        start = Clock::now();
        image = raymaps::relight(input, tables);
        best_s = std::min(best_s, secondsSince(start));
    }
    const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / o.repeat;
    const std::string sparkle =
        applySparkle(o.sparkle, *map, recipe, effect_plan ? &*effect_plan : nullptr, image);
    raymaps::writeImage(image, o.out, o.exposure_ev);
    std::printf("relit %s: %d x %d, %llu paint pixels\n", o.out.c_str(), image.width, image.height,
                static_cast<unsigned long long>(map->header().paint_pixels));
    std::string model = o.preset;
    if (o.sparkle.plan)
        model += ", plan: orders " + std::to_string(settings.orders) + ", bands " +
                 std::to_string(settings.bands) + ", slices " + std::to_string(settings.slices);
    std::printf("load %.1f ms, decode %.1f ms, fast model (%s) %.1f ms, relight tables %.1f ms, relight %.2f "
                "ms%s, %.2f ms CPU (mean over threads and repeats)\n",
                1e3 * load_s, 1e3 * input.seconds(), model.c_str(), 1e3 * brdf_s, 1e3 * tables_s,
                1e3 * best_s, o.repeat > 1 ? " (best of --repeat)" : "", 1e3 * cpu_s);
    if (effect_plan) {
        std::printf("plan (preset %s, tolerance dE00 %.2g per pixel, 99th percentile; %.1f ms), %s:\n",
                    std::string(presetName(preset)).c_str(), effect_plan->tolerance_de, 1e3 * plan_s,
                    o.sparkle.plan ? "applied" : "sparkle decision applied (--plan applies the rest)");
        for (const std::string& line : appliedPlanLines(o.sparkle, *effect_plan))
            std::printf("%s\n", line.c_str());
    }
    if (!sparkle.empty()) std::printf("%s\n", sparkle.c_str());
    return 0;
}

// The intermediate ray map of `render` is removed however the command ends.
class RemoveOnExit {
public:
    explicit RemoveOnExit(std::filesystem::path path) : m_path(std::move(path)) {}
    RemoveOnExit(const RemoveOnExit&) = delete;
    RemoveOnExit& operator=(const RemoveOnExit&) = delete;
    RemoveOnExit(RemoveOnExit&&) = delete;
    RemoveOnExit& operator=(RemoveOnExit&&) = delete;
    ~RemoveOnExit() {
        std::error_code ec;
        std::filesystem::remove(m_path, ec);
    }

private:
    std::filesystem::path m_path;
};

struct ReferenceOptions {
    RelightOptions image;
    std::string scene;
    raymaps::ReferenceSettings settings;
    int cells = 4;
    int orders = 4;
    int width = 0;
    int height = 0;
};

int reference(const ReferenceOptions& o) {
    checkImagePath(o.image.out);
    raymaps::Scene scene = raymaps::loadSceneFile(o.scene);
    applySize(scene, o.width, o.height);
    const Recipe recipe = loadRecipeFile(o.image.recipe);
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(presetFromName(o.image.preset)));
    const raymaps::RelightTables tables(brdf, o.cells, o.orders);
    const auto start = Clock::now();
    const raymaps::ReferenceImage image =
        raymaps::renderReference(scene, tables, o.settings, terminalProgress("reference"));
    raymaps::writeImage(image.mean, o.image.out, o.image.exposure_ev);
    std::printf("reference %s: %d x %d, %d samples per pixel, %.2f s\n", o.image.out.c_str(),
                image.mean.width, image.mean.height, o.settings.samples_per_pixel, secondsSince(start));
    return 0;
}

}  // namespace

void addRaymapCommands(CLI::App& app, CommandAction& action) {
    auto b = std::make_shared<BuildOptions>();
    CLI::App* raymap = app.add_subcommand(kRaymapCommand.name, kRaymapCommand.description);
    raymap->require_subcommand(1);
    CLI::App* cmd = raymap->add_subcommand("build", "Trace SCENE.json once and write its ray map");
    cmd->add_option("scene", b->scene, "Scene JSON file")->required();
    cmd->add_option("--out", b->out, "Ray-map file to write (.prm)")->required();
    addBuildOptions(cmd, *b);
    cmd->add_option("--scene-unit", b->settings.scene_unit_m,
                    "One scene unit in metres, stored in the map (sparkle and plan: pixel footprints)")
        ->capture_default_str();
    cmd->callback([b, &action] {
        action = [b] {
            build(*b, b->out);
            return 0;
        };
    });

    auto r = std::make_shared<RelightOptions>();
    CLI::App* relight = app.add_subcommand(kRelightCommand.name, kRelightCommand.description);
    relight->add_option("map", r->map, "Ray-map file (.prm)")->required();
    addRelightOptions(relight, *r);
    addSparkleOptions(relight, r->sparkle);
    relight->add_option("--repeat", r->repeat, "Relight this many times and report the best time")
        ->capture_default_str();
    relight->callback([r, &action] { action = [r] { return relightMap(*r, r->map); }; });

    auto ro = std::make_shared<ReferenceOptions>();
    CLI::App* ref = app.add_subcommand(kReferenceCommand.name, kReferenceCommand.description);
    ref->add_option("scene", ro->scene, "Scene JSON file")->required();
    addRelightOptions(ref, ro->image);
    ref->add_option("--spp", ro->settings.samples_per_pixel, "Paths per pixel")->capture_default_str();
    ref->add_option("--seed", ro->settings.seed, "Random seed")->capture_default_str();
    ref->add_option("--width", ro->width, "Image width (default: the scene camera's)");
    ref->add_option("--height", ro->height, "Image height (default: the scene camera's)");
    ref->callback([ro, &action] { action = [ro] { return reference(*ro); }; });

    auto rb = std::make_shared<BuildOptions>();
    auto rr = std::make_shared<RelightOptions>();
    CLI::App* render = app.add_subcommand(kRenderCommand.name, kRenderCommand.description);
    render->add_option("scene", rb->scene, "Scene JSON file")->required();
    addRelightOptions(render, *rr);
    addSparkleOptions(render, rr->sparkle);
    addBuildOptions(render, *rb);
    render->callback([rb, rr, &action] {
        action = [rb, rr] {
            const std::filesystem::path map = std::filesystem::temp_directory_path() /
                                              ("paintlab-render-" + std::to_string(getpid()) + ".prm");
            checkImagePath(rr->out);
            (void)presetFromName(rr->preset);
            // --scene-unit goes into the map, which the relight then reads.
            rb->settings.scene_unit_m = rr->sparkle.scene_unit_m;
            // The recipe is known before the precompute: its own colour, not
            // the grey stand-in, is the paint that secondary rays meet (paint
            // seen by paint in a mirror; raymaps/paint_proxy.h).
            rb->settings.paint_proxy_albedo = raymaps::paintProxyAlbedo(
                computeLayeredBrdf(loadRecipeFile(rr->recipe), presetSettings(Preset::Preview)));
            const RemoveOnExit remove(map);
            build(*rb, map);
            return relightMap(*rr, map);
        };
    });
}

}  // namespace paintlab::cli
