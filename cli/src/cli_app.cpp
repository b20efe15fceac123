// The application both programs run (cli_app.h). Exit codes are a public
// contract: 0 ok, 2 bad input, 1 internal error (or a database that is
// locked, read-only or on a full disk).

#include "cli_app.h"

#include "paintlab/database/database.h"
#include "paintlab/engine/error.h"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

namespace paintlab::cli {

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;

int run(int argc, char** argv, const HeavyCommands& heavy) {
    CLI::App app{"PaintLab command line: validate recipes, run the fast model, colour metrics.\n"
                 "Exit codes: 0 ok, 2 bad input (file and field named on stderr), 1 internal error."};
    app.set_version_flag("--version", std::string("paintlab-cli ") + PAINTLAB_VERSION);
    app.require_subcommand(1);

    CommandAction action;
    addRecipeCommands(app, action);
    addSlabCommand(app, action);
    addBrdfCommands(app, action);
    addAccuracyCommand(app, action);
    heavy.add_full_model(app, action);
    addDbCommands(app, action);
    addPluginsCommand(app, action);
    heavy.add_scene(app, action);

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
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const db::DatabaseError& e) {
        // A bad database file is bad input; a locked, read-only or full one is not.
        std::cerr << "error: " << e.what() << '\n';
        return e.isBadFile() ? kExitBadInput : kExitInternal;
    }
}

}  // namespace

int runCli(int argc, char** argv, const HeavyCommands& heavy) {
    try {
        return run(argc, argv, heavy);
    } catch (const std::exception& e) {
        std::cerr << "internal error: " << e.what() << '\n';
    } catch (...) {
        std::cerr << "internal error: unknown exception\n";
    }
    return kExitInternal;
}

}  // namespace paintlab::cli
