// paintlab-cli: the scriptable face of PaintLab.
// Exit codes are a public contract: 0 ok, 2 bad input, 1 internal error (or a
// database that is locked, read-only or on a full disk).

#include "commands.h"
#include "paintlab/database/database.h"
#include "paintlab/engine/error.h"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;

int run(int argc, char** argv) {
    CLI::App app{"PaintLab command line: validate recipes, run the fast model, colour metrics.\n"
                 "Exit codes: 0 ok, 2 bad input (file and field named on stderr), 1 internal error."};
    app.set_version_flag("--version", std::string("paintlab-cli ") + PAINTLAB_VERSION);
    app.require_subcommand(1);

    paintlab::cli::CommandAction action;
    paintlab::cli::addRecipeCommands(app, action);
    paintlab::cli::addSlabCommand(app, action);
    paintlab::cli::addBrdfCommands(app, action);
    paintlab::cli::addAccuracyCommand(app, action);
    paintlab::cli::addMcCommands(app, action);
    paintlab::cli::addDbCommands(app, action);
    paintlab::cli::addRaymapCommands(app, action);
    paintlab::cli::addPlanCommand(app, action);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kExitBadInput;
    }

    try {
        return action ? action() : kExitOk;
    } catch (const paintlab::InputError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const paintlab::db::DatabaseError& e) {
        // A bad database file is bad input; a locked, read-only or full one is not.
        std::cerr << "error: " << e.what() << '\n';
        return e.isBadFile() ? kExitBadInput : kExitInternal;
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "internal error: " << e.what() << '\n';
    } catch (...) {
        std::cerr << "internal error: unknown exception\n";
    }
    return kExitInternal;
}
