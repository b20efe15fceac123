// `db init|list|show|recipe-save|recipe-history|backup`: the ingredient and
// recipe database. One function per subcommand; import, export, production
// and measurements are in db_exchange_commands.cpp, registered from addDbCommands.
//
// --db FILE selects the database. Without it the user's database is used
// (demo.h: $XDG_DATA_HOME/paintlab/paintlab.db), created from the demo data
// on first use. An explicit --db FILE must exist, except for `db init`.

#include "commands.h"
#include "db_cli.h"
#include "recipe_text.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <memory>

namespace paintlab::cli {

// Opens the chosen database. The default one is filled from the demo while it
// holds nothing (on first use, or after a first use that was interrupted).
db::Database openCliDatabase(const std::string& db_file, bool create) {
    if (!db_file.empty()) {
        db::OpenOptions open;
        open.create = create;
        return db::Database::open(db_file, open);
    }
    db::Database database = db::Database::open(db::defaultDatabasePath());
    if (!database.isReadOnly()) {
        const auto summary = db::initDemoDatabase(database);
        if (!summary.already_initialised)
            std::cerr << "created " << database.file().string() << " from the demo data ("
                      << summary.ingredients_added << " ingredients, " << summary.recipes_added
                      << " recipes)\n";
    }
    return database;
}

namespace {

using nlohmann::ordered_json;

struct DbOptions {
    std::string db_file;  // empty: the user's default database
    bool json = false;
    // list
    std::string kind;
    std::vector<std::string> tags;
    std::string name_contains;
    // show, recipe-history
    std::string name;
    int version = 0;  // 0: the latest
    // recipe-save
    std::string recipe_file;
    std::string author;
    std::string note;
    bool strict = false;
    // backup
    std::string target;
};

db::Database openDatabase(const DbOptions& options, bool create) {
    return openCliDatabase(options.db_file, create);
}

// Case-insensitive substring test (ASCII), as the ingredient search does.
bool containsIgnoringCase(std::string_view text, std::string_view part) {
    const auto lower = [](std::string_view in) {
        std::string out(in);
        for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return out;
    };
    return lower(text).find(lower(part)) != std::string::npos;
}

std::optional<db::IngredientKind> kindOption(const std::string& kind) {
    if (kind.empty()) return std::nullopt;
    auto parsed = db::parseIngredientKind(kind);
    if (!parsed)
        throw InputError("<argument>", "--kind",
                         "unknown kind '" + kind +
                             "' (binder, pigment, mirror_flake, interference_flake, substrate)");
    return parsed;
}

ordered_json versionJson(const db::RecipeVersionInfo& info) {
    return {{"recipe", info.recipe_name}, {"version", info.version},
            {"author", info.author},      {"created_at", info.created_at},
            {"note", info.note},          {"checksum_sha256", info.checksum_sha256}};
}

int runInit(const DbOptions& options) {
    db::Database database = options.db_file.empty() ? db::Database::open(db::defaultDatabasePath())
                                                    : db::Database::open(options.db_file);
    const auto summary = db::initDemoDatabase(database);
    if (options.json) {
        std::cout << ordered_json{{"database", database.file().string()},
                                  {"schema_version", database.schemaVersion()},
                                  {"already_initialised", summary.already_initialised},
                                  {"ingredients_added", summary.ingredients_added},
                                  {"recipes_added", summary.recipes_added},
                                  {"measurements_added", summary.measurements_added}}
                         .dump(2)
                  << '\n';
    } else if (summary.already_initialised) {
        std::cout << database.file().string() << ": already holds data; nothing added\n";
    } else {
        std::cout << database.file().string() << ": demo database created (" << summary.ingredients_added
                  << " ingredients, " << summary.recipes_added << " recipes, schema version "
                  << database.schemaVersion() << ")\n";
    }
    return 0;
}

int runList(const DbOptions& options) {
    db::Database database = openDatabase(options, false);
    db::IngredientFilter filter;
    filter.kind = kindOption(options.kind);
    filter.tags = options.tags;
    filter.name_contains = options.name_contains;
    const auto ingredients = db::searchIngredients(database, filter);
    // Recipes are listed unless the filter is about ingredients only.
    const bool with_recipes = options.kind.empty() && options.tags.empty();
    std::vector<db::RecipeSummary> recipes;
    if (with_recipes)
        for (auto& recipe : db::listRecipes(database))
            if (containsIgnoringCase(recipe.name, options.name_contains))
                recipes.push_back(std::move(recipe));

    if (options.json) {
        ordered_json out{{"database", database.file().string()},
                         {"ingredients", ordered_json::array()},
                         {"recipes", ordered_json::array()}};
        for (const auto& i : ingredients) {
            ordered_json item{
                {"id", i.id}, {"kind", db::ingredientKindName(i.kind)}, {"name", i.name}, {"tags", i.tags}};
            item["density_g_cm3"] = i.density_g_cm3 ? ordered_json(*i.density_g_cm3) : ordered_json(nullptr);
            out["ingredients"].push_back(item);
        }
        for (const auto& r : recipes)
            out["recipes"].push_back({{"name", r.name},
                                      {"latest_version", r.latest_version},
                                      {"latest_created_at", r.latest_created_at},
                                      {"latest_author", r.latest_author}});
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::cout << "Ingredients (" << ingredients.size() << "):\n";
    for (const auto& i : ingredients) {
        std::cout << "  " << i.id << "  " << db::ingredientKindName(i.kind) << "  " << i.name;
        if (!i.tags.empty()) {
            std::cout << "  [";
            for (std::size_t t = 0; t < i.tags.size(); ++t) std::cout << (t > 0 ? ", " : "") << i.tags[t];
            std::cout << "]";
        }
        std::cout << '\n';
    }
    if (with_recipes) {
        std::cout << "Recipes (" << recipes.size() << "):\n";
        for (const auto& r : recipes)
            std::cout << "  " << r.name << "  v" << r.latest_version << "  " << r.latest_created_at << "  "
                      << r.latest_author << '\n';
    }
    return 0;
}

void printIngredient(const db::Ingredient& ing, db::Database& database) {
    std::cout << db::ingredientKindName(ing.kind()) << " '" << ing.name << "' (id " << ing.id << ")\n";
    if (!ing.description.empty()) std::cout << "  description: " << ing.description << '\n';
    if (!ing.source.empty()) std::cout << "  source: " << ing.source << '\n';
    if (ing.density_g_cm3)
        std::cout << "  density: " << *ing.density_g_cm3 << " g/cm3"
                  << (ing.density_source.empty() ? "" : " (" + ing.density_source + ")") << '\n';
    if (!ing.tags.empty()) {
        std::cout << "  tags:";
        for (const auto& tag : ing.tags) std::cout << ' ' << tag;
        std::cout << '\n';
    }
    const auto& limits = ing.limits;
    if (limits.max_volume_fraction)
        std::cout << "  max volume fraction: " << *limits.max_volume_fraction << '\n';
    if (limits.min_thickness_um || limits.max_thickness_um)
        std::cout << "  film thickness: " << limits.min_thickness_um.value_or(0.0) << " to "
                  << (limits.max_thickness_um ? std::to_string(*limits.max_thickness_um) : std::string("-"))
                  << " µm\n";
    for (const auto& s : db::ingredientSpectra(database, ing.id)) {
        std::cout << "  spectrum " << s.quantity << " [" << s.info.unit << "]: " << s.spectrum.values().size()
                  << (s.spectrum.isConstant() ? " value" : " samples");
        if (!s.spectrum.isConstant())
            std::cout << ", " << s.spectrum.wavelengthsNm().front() << "-"
                      << s.spectrum.wavelengthsNm().back() << " nm";
        std::cout << ", " << s.spectrum.minValue() << " to " << s.spectrum.maxValue() << '\n';
        if (!s.info.source.empty()) std::cout << "    source: " << s.info.source << '\n';
    }
}

int runShow(const DbOptions& options) {
    db::Database database = openDatabase(options, false);
    const auto kind = kindOption(options.kind);
    // A recipe of that name first (unless a kind asks for an ingredient), then ingredients.
    if (!kind) {
        const auto recipes = db::listRecipes(database);
        const bool is_recipe = std::any_of(recipes.begin(), recipes.end(),
                                           [&](const auto& r) { return r.name == options.name; });
        if (is_recipe) {
            const auto stored = db::loadRecipeVersion(
                database, options.name, options.version > 0 ? std::optional(options.version) : std::nullopt);
            if (options.json) {
                ordered_json out = versionJson(stored.info);
                out["recipe_json"] = ordered_json::parse(recipeToJson(stored.recipe));
                std::cout << out.dump(2) << '\n';
            } else {
                std::cout << "Recipe '" << stored.info.recipe_name << "' version " << stored.info.version
                          << ", saved " << stored.info.created_at << " by " << stored.info.author << '\n';
                if (!stored.info.note.empty()) std::cout << "Note: " << stored.info.note << '\n';
                std::cout << "SHA-256: " << stored.info.checksum_sha256 << "\n\n"
                          << describeRecipe(stored.recipe);
            }
            return 0;
        }
    }
    std::vector<db::Ingredient> found;
    for (int k = 0; k < 5; ++k) {
        const auto each = static_cast<db::IngredientKind>(k);
        if (kind && *kind != each) continue;
        if (auto ingredient = db::findIngredient(database, each, options.name))
            found.push_back(std::move(*ingredient));
    }
    if (found.empty())
        throw InputError(database.file().string(), "'" + options.name + "'",
                         kind ? "no such ingredient of this kind" : "no recipe or ingredient of this name");
    if (found.size() > 1)
        throw InputError(database.file().string(), "'" + options.name + "'",
                         "several ingredients have this name; choose one with --kind");
    if (options.json)
        std::cout << db::ingredientsToJson(found);
    else
        printIngredient(found.front(), database);
    return 0;
}

int runRecipeSave(const DbOptions& options) {
    const Recipe recipe = loadRecipeFile(options.recipe_file);
    db::Database database = openDatabase(options, false);
    db::SaveOptions save;
    save.author = options.author;
    if (save.author.empty()) {
        const char* user = std::getenv("USER");  // NOLINT(concurrency-mt-unsafe): single-threaded here
        save.author = user != nullptr && *user != '\0' ? user : "unknown";
    }
    save.note = options.note;
    save.require_known_ingredients = options.strict;
    save.source = options.recipe_file;
    const auto saved = db::saveRecipeVersion(database, recipe, save);
    for (const auto& missing : saved.unlinked)
        std::cerr << "warning: " << options.recipe_file << ": " << missing
                  << ": not in the database; saved with the recipe's own data, unlinked\n";
    if (options.json) {
        std::cout << ordered_json{{"recipe", saved.recipe_name},
                                  {"version", saved.version},
                                  {"created", saved.created},
                                  {"checksum_sha256", saved.checksum_sha256},
                                  {"unlinked", saved.unlinked}}
                         .dump(2)
                  << '\n';
    } else if (saved.created) {
        std::cout << "saved '" << saved.recipe_name << "' version " << saved.version << " (SHA-256 "
                  << saved.checksum_sha256 << ")\n";
    } else {
        std::cout << "unchanged: '" << saved.recipe_name << "' is identical to its version " << saved.version
                  << "; no new version\n";
    }
    return 0;
}

int runRecipeHistory(const DbOptions& options) {
    db::Database database = openDatabase(options, false);
    const auto history = db::recipeHistory(database, options.name);
    if (options.json) {
        ordered_json out = ordered_json::array();
        for (const auto& info : history) out.push_back(versionJson(info));
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::cout << "Recipe '" << options.name << "': " << history.size()
              << (history.size() == 1 ? " version\n" : " versions\n");
    for (const auto& info : history) {
        std::cout << "  v" << info.version << "  " << info.created_at << "  " << info.author << "  "
                  << info.checksum_sha256.substr(0, 12);
        if (!info.note.empty()) std::cout << "  " << info.note;
        std::cout << '\n';
    }
    return 0;
}

int runBackup(const DbOptions& options) {
    db::Database database = openDatabase(options, false);
    database.backupTo(options.target);
    std::cout << "backed up " << database.file().string() << " to " << options.target << '\n';
    return 0;
}

// Registers one subcommand whose action runs run(options).
CLI::App* addSubcommand(CLI::App& group, const std::string& name, const std::string& help,
                        const std::shared_ptr<DbOptions>& options, CommandAction& action,
                        int (*run)(const DbOptions&)) {
    CLI::App* command = group.add_subcommand(name, help);
    command->add_option("--db", options->db_file,
                        "Database file (default: the user's, created from the demo)");
    command->callback([options, &action, run] { action = [options, run] { return run(*options); }; });
    return command;
}

}  // namespace

void addDbCommands(CLI::App& app, CommandAction& action) {
    auto options = std::make_shared<DbOptions>();
    CLI::App* group = app.add_subcommand("db", "The ingredient and recipe database (SQLite)");
    group->require_subcommand(1);

    CLI::App* init = addSubcommand(*group, "init", "Create the database from the demo data (if it is empty)",
                                   options, action, runInit);
    init->add_flag("--json", options->json, "Print the result as JSON");

    CLI::App* list = addSubcommand(*group, "list", "List ingredients and recipes", options, action, runList);
    list->add_option("--kind", options->kind, "Only ingredients of this kind (binder, pigment, ...)");
    list->add_option("--tag", options->tags, "Only ingredients with this tag (repeatable: all of them)");
    list->add_option("--name", options->name_contains, "Only names containing this text");
    list->add_flag("--json", options->json, "Print as JSON");

    CLI::App* show =
        addSubcommand(*group, "show", "Show a recipe version or an ingredient", options, action, runShow);
    show->add_option("name", options->name, "Recipe or ingredient name")->required();
    show->add_option("--version", options->version, "Recipe version (default: the latest)")
        ->check(CLI::PositiveNumber);
    show->add_option("--kind", options->kind, "Show the ingredient of this kind");
    show->add_flag("--json", options->json,
                   "Print as JSON (recipe version with its canonical JSON, or the ingredient)");

    CLI::App* save = addSubcommand(*group, "recipe-save", "Save a recipe file as a new version", options,
                                   action, runRecipeSave);
    save->add_option("recipe", options->recipe_file, "Recipe JSON file")->required();
    save->add_option("--author", options->author, "Who saves it (default: $USER)");
    save->add_option("--note", options->note, "What changed and why");
    save->add_flag("--strict", options->strict,
                   "Refuse a recipe using ingredients the database does not hold");
    save->add_flag("--json", options->json, "Print the result as JSON");

    CLI::App* history = addSubcommand(*group, "recipe-history", "List every version of a recipe", options,
                                      action, runRecipeHistory);
    history->add_option("name", options->name, "Recipe name")->required();
    history->add_flag("--json", options->json, "Print as JSON");

    CLI::App* backup = addSubcommand(*group, "backup", "Copy the database safely while it may be in use",
                                     options, action, runBackup);
    backup->add_option("target", options->target, "New file to write the copy to")->required();

    addDbExchangeCommands(*group, action);
}

}  // namespace paintlab::cli
