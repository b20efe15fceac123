// paintlab-cli: the scriptable face of PaintLab (cli/README.md).
// This front end links the fast model and the database only, so that the
// light commands (validate, show, slab, brdf, eval, multiangle, accuracy,
// db) start in milliseconds without the image, mesh and ray-tracing
// libraries. A command line that names a command of the full model or the
// ray maps (helper_commands.h) is handed, argv unchanged, to
// paintlab-cli-full: beside this program in the build tree, in
// PAINTLAB_CLI_HELPER_DIR (relative to this program's folder) when installed.

#include "cli_app.h"
#include "helper_commands.h"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <iostream>
#include <span>
#include <string_view>
#include <system_error>

namespace {

namespace fs = std::filesystem;
using paintlab::cli::CommandAction;
using paintlab::cli::CommandSummary;

constexpr const char* kHelperName = "paintlab-cli-full";
constexpr int kExitInternal = 1;

bool isHelperCommand(std::string_view arg) {
    for (const CommandSummary& c : paintlab::cli::kFullModelCommands)
        if (arg == c.name) return true;
    for (const CommandSummary& c : paintlab::cli::kSceneCommands)
        if (arg == c.name) return true;
    return false;
}

// Any argument, not only the command's position: the helper then parses the
// line exactly as the single program did. An argument that merely equals a
// command name (a file called "plan") costs the helper's start-up, never a
// different result.
bool namesHelperCommand(std::span<char*> args) {
    for (const char* arg : args.subspan(1))
        if (isHelperCommand(arg)) return true;
    return false;
}

fs::path helperPath() {
    std::error_code ec;
    const fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
    for (const fs::path& candidate : {dir / kHelperName, dir / PAINTLAB_CLI_HELPER_DIR / kHelperName})
        if (access(candidate.c_str(), X_OK) == 0) return candidate;
    return dir / PAINTLAB_CLI_HELPER_DIR / kHelperName;  // named in the error below
}

// Replaces this process by the helper (same argv, streams and exit code);
// returns only if that fails.
int runHelper(char** argv) {
    const fs::path helper = helperPath();
    execv(helper.c_str(), argv);
    std::cerr << "internal error: cannot run " << helper.string() << " (installed with paintlab-cli): "
              << std::error_code(errno, std::generic_category()).message() << '\n';
    return kExitInternal;
}

// An entry that names a helper command in --help. It is never chosen, since
// main() hands every line naming one to the helper; if it were, the helper runs.
paintlab::cli::AddCommands namingOnly(std::span<const CommandSummary> commands, char** argv) {
    return [commands, argv](CLI::App& app, CommandAction& action) {
        for (const CommandSummary& c : commands)
            app.add_subcommand(c.name, c.description)->callback([&action, argv] {
                action = [argv] { return runHelper(argv); };
            });
    };
}

}  // namespace

int main(int argc, char** argv) {
    if (namesHelperCommand({argv, static_cast<std::size_t>(argc)})) return runHelper(argv);
    return paintlab::cli::runCli(argc, argv,
                                 {namingOnly(paintlab::cli::kFullModelCommands, argv),
                                  namingOnly(paintlab::cli::kSceneCommands, argv)});
}
