#pragma once
// `--sparkle on|off|plan` of `relight` and `render` (issue 7): after the
// relight, the sparkle pass (raymaps/sparkle_pass.h) adds the paint's glints;
// `plan` asks the effect planner (from the ray map's lights and footprints)
// whether they are visible at this scene's footprints first.

#include "paintlab/engine/layered_brdf.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"

#include <string>

namespace CLI {
class App;
}

namespace paintlab::cli {

struct SparkleOption {
    std::string mode = "off";  // on, off, plan
    double scene_unit_m = 1.0;
    std::string camera_scene;  // `render`: the scene whose camera gives the pixel angle
    int camera_height = 0;     // `render --height`
};

void addSparkleOptions(CLI::App* command, SparkleOption& o);

// Runs the sparkle pass on `image` if the mode says so; returns the line to
// print ("" for off). Throws InputError for a bad setting.
std::string applySparkle(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                         Preset preset, raymaps::RgbImage& image);

}  // namespace paintlab::cli
