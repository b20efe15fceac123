// paintlab-cli-full: every command of paintlab-cli, with the Monte Carlo and
// ray-map libraries linked. paintlab-cli runs the light commands itself and
// executes this program, with its own argv, for the others (main.cpp).

#include "cli_app.h"

namespace {

void addFullModelCommands(CLI::App& app, paintlab::cli::CommandAction& action) {
    paintlab::cli::addMcCommands(app, action);
    paintlab::cli::addFitCommand(app, action);
}

void addSceneCommands(CLI::App& app, paintlab::cli::CommandAction& action) {
    paintlab::cli::addRaymapCommands(app, action);
    paintlab::cli::addPlanCommand(app, action);
}

}  // namespace

int main(int argc, char** argv) {
    return paintlab::cli::runCli(argc, argv, {addFullModelCommands, addSceneCommands});
}
