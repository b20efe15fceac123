#pragma once
// The demo database and where the user's database lives.
//
// The demo content is compiled into the library (database/CMakeLists.txt
// embeds packaging/demo/ingredients/demo-ingredients.json and the five demo
// recipes), so an installed program needs no data folder.

#include "paintlab/database/database.h"

#include <filesystem>

namespace paintlab::db {

struct DemoSummary {
    int ingredients_added = 0;
    int recipes_added = 0;             // recipe versions created
    int measurements_added = 0;        // made-up panels for the Match tab (packaging/demo/measurements/)
    bool already_initialised = false;  // the database held ingredients or recipes: nothing was added
};

// Fills an empty database with the demo ingredients and recipes, in one
// transaction. A database that already holds ingredients or recipes is left
// alone (already_initialised). Throws DatabaseError naming the file.
DemoSummary initDemoDatabase(Database& db);

// $XDG_DATA_HOME/paintlab/paintlab.db, or ~/.local/share/paintlab/paintlab.db
// when XDG_DATA_HOME is unset or not absolute (XDG Base Directory spec).
// Throws Error if neither XDG_DATA_HOME nor HOME is usable.
std::filesystem::path defaultDatabasePath();

}  // namespace paintlab::db
