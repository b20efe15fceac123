#pragma once
// The command-line application shared by paintlab-cli (the light front end,
// main.cpp) and paintlab-cli-full (every command, full_main.cpp): the same
// commands in the same order, the same parsing, messages and exit codes.

#include "commands.h"

#include <functional>

namespace paintlab::cli {

// The registrations that differ between the two programs: the real commands
// (addMcCommands; addSceneCommands) in the helper, entries that only name
// them (helper_commands.h) in the front end.
using AddCommands = std::function<void(CLI::App& app, CommandAction& action)>;
struct HeavyCommands {
    AddCommands add_full_model;  // mc, compare
    AddCommands add_scene;       // raymap, relight, reference, render, plan
};

// Parses argv and runs the chosen command; returns the exit code (0 ok,
// 2 bad input, 1 internal error). Never throws: every error is on stderr.
int runCli(int argc, char** argv, const HeavyCommands& heavy);

}  // namespace paintlab::cli
