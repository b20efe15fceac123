// `validate` and `show`: the recipe-file commands.

#include "commands.h"
#include "recipe_text.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/recipe_validation.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace paintlab::cli {

namespace {

struct RecipeOptions {
    std::string path;
    bool json = false;
};

std::string severityName(Severity s) { return s == Severity::Error ? "error" : "warning"; }

int runValidate(const RecipeOptions& options) {
    // Structural problems (syntax, types, missing fields) throw and become exit 2 in main.
    const Recipe recipe = parseRecipeFile(options.path);
    const auto problems = checkRecipe(recipe);
    bool has_error = false;
    for (const auto& p : problems) has_error = has_error || p.severity == Severity::Error;

    if (options.json) {
        nlohmann::ordered_json out;
        out["file"] = options.path;
        out["valid"] = !has_error;
        out["problems"] = nlohmann::ordered_json::array();
        for (const auto& p : problems)
            out["problems"].push_back(
                {{"severity", severityName(p.severity)}, {"field", p.field}, {"message", p.message}});
        std::cout << out.dump(2) << '\n';
    } else {
        for (const auto& p : problems)
            std::cerr << severityName(p.severity) << ": " << options.path << ": " << p.field << ": "
                      << p.message << '\n';
        if (!has_error)
            std::cout << options.path << ": valid recipe '" << recipe.name << "', " << recipe.layers.size()
                      << (recipe.layers.size() == 1 ? " layer" : " layers") << '\n';
    }
    return has_error ? 2 : 0;
}

int runShow(const RecipeOptions& options) {
    const Recipe recipe = loadRecipeFile(options.path);
    if (options.json)
        std::cout << recipeToJson(recipe);
    else
        std::cout << describeRecipe(recipe);
    return 0;
}

}  // namespace

void addRecipeCommands(CLI::App& app, CommandAction& action) {
    auto options = std::make_shared<RecipeOptions>();

    CLI::App* validate =
        app.add_subcommand("validate", "Check a recipe file; list every problem with its field");
    validate->add_option("recipe", options->path, "Recipe JSON file")->required();
    validate->add_flag("--json", options->json, "Print the result as JSON on stdout");
    validate->callback([options, &action] { action = [options] { return runValidate(*options); }; });

    CLI::App* show = app.add_subcommand("show", "Print a validated recipe, as text or canonical JSON");
    show->add_option("recipe", options->path, "Recipe JSON file")->required();
    show->add_flag("--json", options->json, "Print the canonical JSON of the recipe");
    show->callback([options, &action] { action = [options] { return runShow(*options); }; });
}

}  // namespace paintlab::cli
