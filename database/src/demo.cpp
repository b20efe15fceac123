// The demo database (demo.h): the embedded demo ingredients, recipes and
// made-up measurement,
// and the default location of the user's database.

#include "paintlab/database/demo.h"

#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/measurement_files.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/recipe_json.h"

#include "embedded_files.h"
#include "sqlite.h"

#include <cstdlib>

namespace paintlab::db {

namespace {

bool isEmpty(const detail::Connection& c) {
    detail::Statement s(c, "SELECT (SELECT count(*) FROM ingredient) + (SELECT count(*) FROM recipe)");
    return s.step() && s.integer(0) == 0;
}

}  // namespace

DemoSummary initDemoDatabase(Database& db) {
    const detail::Connection& c = db.impl().connection;
    DemoSummary summary;
    // One transaction around everything (the repository functions' own
    // transactions become savepoints): a half-filled demo database is never left.
    detail::Transaction transaction(c, detail::Transaction::Mode::Write);
    if (!isEmpty(c)) {
        summary.already_initialised = true;
        return summary;
    }
    const auto& files = detail::demoFiles();
    for (const auto& file : files) {
        const std::string source = "<demo>/" + file.name;
        if (file.name.ends_with("ingredients.json")) {
            for (const auto& ingredient : parseIngredientsJson(file.text, source)) {
                createIngredient(db, ingredient);
                ++summary.ingredients_added;
            }
        }
    }
    for (const auto& file : files) {
        if (!file.name.ends_with("-panel.json")) continue;
        createMeasurement(db, parseMeasurementJson(file.text, "<demo>/measurements/" + file.name));
        ++summary.measurements_added;
    }
    for (const auto& file : files) {
        if (file.name.ends_with("ingredients.json") || file.name.ends_with("-panel.json")) continue;
        const std::string source = "<demo>/recipes/" + file.name;
        const Recipe recipe = parseRecipeJson(file.text, source);
        SaveOptions options;
        options.author = "PaintLab demo";
        options.note = "demo recipe from packaging/demo/recipes/" + file.name;
        options.source = source;
        if (saveRecipeVersion(db, recipe, options).created) ++summary.recipes_added;
    }
    transaction.commit();
    return summary;
}

std::filesystem::path defaultDatabasePath() {
    // XDG Base Directory spec: a relative XDG_DATA_HOME is invalid and ignored.
    const char* xdg = std::getenv("XDG_DATA_HOME");  // NOLINT(concurrency-mt-unsafe): read once at start-up
    if (xdg != nullptr && *xdg != '\0' && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "paintlab" / "paintlab.db";
    const char* home = std::getenv("HOME");  // NOLINT(concurrency-mt-unsafe)
    if (home == nullptr || *home == '\0')
        throw Error(
            "cannot find the default database: neither XDG_DATA_HOME nor HOME is set (use --db FILE)");
    return std::filesystem::path(home) / ".local" / "share" / "paintlab" / "paintlab.db";
}

}  // namespace paintlab::db
