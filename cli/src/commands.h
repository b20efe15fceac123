#pragma once
// Each group of CLI commands registers itself on the application; cli_app.cpp
// lists the groups explicitly (after Mayo's src/app/main.cpp). `mc`,
// `compare`, the ray-map commands and `plan` are linked into paintlab-cli-full
// only (helper_commands.h).

#include <functional>

namespace CLI {
class App;
}

namespace paintlab::cli {

// What a subcommand runs once parsing succeeded; returns the exit code.
using CommandAction = std::function<int()>;

// Registers `validate` and `show`. The chosen command's action is stored in action.
void addRecipeCommands(CLI::App& app, CommandAction& action);

// Registers `slab`: totals of a single raw-medium slab (Prahl's UR1, UT1, URU, UTU).
void addSlabCommand(CLI::App& app, CommandAction& action);

// Registers `brdf`, `eval` and `multiangle` (the fast model).
void addBrdfCommands(CLI::App& app, CommandAction& action);

// Registers `accuracy`: the error-vs-time table of the fast model's knobs and presets.
void addAccuracyCommand(CLI::App& app, CommandAction& action);

// Registers `mc` and `compare`: the Monte Carlo full model and its comparison with the fast model.
void addMcCommands(CLI::App& app, CommandAction& action);

// Registers `fit`: a recipe fitted to measurements (engine fit/fit.h, issue 28).
void addFitCommand(CLI::App& app, CommandAction& action);

// Registers `db` and its subcommands: init, list, show, recipe-save, recipe-history, backup.
void addDbCommands(CLI::App& app, CommandAction& action);

// Registers `plugins`: the format plugins loaded and refused (plugins/registry.h).
void addPluginsCommand(CLI::App& app, CommandAction& action);

// Registers `raymap build`, `relight`, `render` and `reference` (ray maps, docs/RAYMAPS.md).
void addRaymapCommands(CLI::App& app, CommandAction& action);

// Registers `plan`: the effect planner's decisions for a recipe in a scene (issue 7).
void addPlanCommand(CLI::App& app, CommandAction& action);

}  // namespace paintlab::cli
