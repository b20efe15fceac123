#pragma once
// The commands that run in paintlab-cli-full, the helper program linked with
// the Monte Carlo and ray-map libraries (Embree, TBB, OpenImageIO, assimp and
// what they load) and the fitter (Ceres). Their names and one-line descriptions are declared once:
// the helper registers the commands with them, the front end (main.cpp) lists
// them in its --help and hands any command line naming one to the helper.

#include <array>

namespace paintlab::cli {

struct CommandSummary {
    const char* name;
    const char* description;
};

inline constexpr CommandSummary kMcCommand{
    "mc",
    "Monte Carlo full model: albedo at 0 and 45 deg, BRDF at the multi-angle geometries, with std errors"};
inline constexpr CommandSummary kCompareCommand{
    "compare", "Fast vs full model at the multi-angle geometries, with the time each took"};
inline constexpr CommandSummary kFitCommand{
    "fit", "Fit a recipe to measurements: parameters with sigma, dE00 per geometry, alternatives"};
inline constexpr CommandSummary kRaymapCommand{"raymap",
                                               "Ray maps: precompute a scene once, relight its paint"};
inline constexpr CommandSummary kRelightCommand{"relight", "Re-shade the paint of a ray map with a recipe"};
inline constexpr CommandSummary kReferenceCommand{
    "reference", "Brute-force path-traced reference of a scene with the paint's RGB BRDF (slow; for tests)"};
inline constexpr CommandSummary kRenderCommand{"render", "raymap build, then relight (the map is not kept)"};
inline constexpr CommandSummary kPlanCommand{
    "plan", "What to simulate for a recipe in a scene, with reasons and accepted errors"};

// In the order the commands are registered (addMcCommands, addFitCommand; addRaymapCommands, addPlanCommand).
inline constexpr std::array kFullModelCommands{kMcCommand, kCompareCommand, kFitCommand};
inline constexpr std::array kSceneCommands{kRaymapCommand, kRelightCommand, kReferenceCommand, kRenderCommand,
                                           kPlanCommand};

}  // namespace paintlab::cli
