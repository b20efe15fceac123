// Opening, schema versions and migrations: a new file gets schema 1 in WAL
// mode; an older schema is migrated step by step; a newer one, another
// program's SQLite file, a file that is not SQLite and a corrupt file are
// refused with an error naming the file, and left byte-identical.

#include "db_test_support.h"
#include "migrations.h"

#include "paintlab/database/database.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"

#include <gtest/gtest.h>

namespace paintlab::db {
namespace {

using test::fileBytes;
using test::rawExec;
using test::rawQuery;
using test::TempDir;

// Expects open to fail with the reason, a message naming the file, and the file unchanged.
void expectRefused(const std::filesystem::path& file, DatabaseError::Reason reason,
                   const std::string& words) {
    const std::string before = fileBytes(file);
    try {
        Database::open(file);
        FAIL() << "opened " << file;
    } catch (const DatabaseError& e) {
        EXPECT_EQ(e.reason(), reason) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), file);
    }
    EXPECT_EQ(fileBytes(file), before) << "a refused file was altered";
}

TEST(DatabaseOpen, NewFileHasLatestSchemaWalAndForeignKeys) {
    TempDir dir;
    const auto file = dir / "sub" / "new.db";  // the folder is created too
    {
        Database db = Database::open(file);
        EXPECT_EQ(db.schemaVersion(), 2);
        EXPECT_EQ(Database::latestSchemaVersion(), 2);
        EXPECT_EQ(db.file(), file);
        EXPECT_FALSE(db.isReadOnly());
        EXPECT_TRUE(db.integrityCheck().empty());
    }
    EXPECT_EQ(rawQuery(file, "PRAGMA journal_mode"), "wal");
    EXPECT_EQ(rawQuery(file, "PRAGMA user_version"), "2");
    EXPECT_EQ(rawQuery(file, "PRAGMA application_id"), std::to_string(detail::kApplicationId));
    EXPECT_EQ(Database::open(file).schemaVersion(), 2);  // a second open migrates nothing
}

TEST(DatabaseOpen, MissingFileWithoutCreateNamesIt) {
    TempDir dir;
    OpenOptions options;
    options.create = false;
    try {
        Database::open(dir / "absent.db", options);
        FAIL();
    } catch (const DatabaseError& e) {
        EXPECT_EQ(e.reason(), DatabaseError::Reason::CannotOpen);
        EXPECT_NE(std::string(e.what()).find("absent.db"), std::string::npos);
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "absent.db"));
}

TEST(DatabaseOpen, NewerSchemaIsRefusedAndLeftByteIdentical) {
    TempDir dir;
    const auto file = dir / "newer.db";
    {
        Database db = Database::open(file);
        saveRecipeVersion(db, test::minimalRecipe(), {"tester", "v1", false, ""});
    }
    ASSERT_EQ(rawExec(file, "PRAGMA user_version = 7"), SQLITE_OK);
    expectRefused(file, DatabaseError::Reason::NewerSchema, "schema version 7 is newer than this build");
    expectRefused(file, DatabaseError::Reason::NewerSchema, "supports (2)");
    EXPECT_FALSE(std::filesystem::exists(file.string() + "-wal") &&
                 std::filesystem::file_size(file.string() + "-wal") > 0);
}

TEST(DatabaseOpen, NotSqliteIsRefused) {
    TempDir dir;
    const auto file = dir / "notes.db";
    std::string text;
    for (int i = 0; i < 200; ++i) text += "This is a lab notebook, not a database. ";
    test::writeBytes(file, text);
    expectRefused(file, DatabaseError::Reason::NotADatabase, "not");
}

TEST(DatabaseOpen, AnotherProgramsSqliteFileIsRefused) {
    TempDir dir;
    const auto file = dir / "other.db";
    {
        sqlite3* raw = nullptr;
        ASSERT_EQ(sqlite3_open(file.c_str(), &raw), SQLITE_OK);
        ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE customers (name TEXT); INSERT INTO customers VALUES ('a')",
                               nullptr, nullptr, nullptr),
                  SQLITE_OK);
        sqlite3_close(raw);
    }
    expectRefused(file, DatabaseError::Reason::NotADatabase, "not a PaintLab database");
    ASSERT_EQ(rawExec(file, "PRAGMA application_id = 42"), SQLITE_OK);
    expectRefused(file, DatabaseError::Reason::NotADatabase, "application_id 42");
}

TEST(DatabaseOpen, CorruptFileIsRefusedWithItsName) {
    TempDir dir;
    const auto file = dir / "corrupt.db";
    {
        Database db = Database::open(file);
        for (int i = 0; i < 5; ++i)
            saveRecipeVersion(db, test::minimalRecipe("r", 10.0 + i), {"tester", "", false, ""});
    }
    // Garbage over the schema table (page 1 after the 100-byte file header).
    test::writeBytes(file, std::string(2000, '\x5a'), 100);
    const std::string before = fileBytes(file);
    try {
        Database db = Database::open(file);
        listRecipes(db);
        FAIL() << "a corrupt database was read";
    } catch (const DatabaseError& e) {
        EXPECT_TRUE(e.reason() == DatabaseError::Reason::Corrupt ||
                    e.reason() == DatabaseError::Reason::NotADatabase)
            << e.what();
        EXPECT_TRUE(e.isBadFile());
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(fileBytes(file), before);
}

TEST(DatabaseOpen, CorruptDataPageIsReportedOnRead) {
    TempDir dir;
    const auto file = dir / "corrupt-page.db";
    {
        Database db = Database::open(file);
        for (int i = 0; i < 40; ++i)
            saveRecipeVersion(db, test::minimalRecipe("recipe " + std::to_string(i), 10.0),
                              {"t", "", false, ""});
    }
    const auto page_size = std::stoll(rawQuery(file, "PRAGMA page_size"));
    const auto root =
        std::stoll(rawQuery(file, "SELECT rootpage FROM sqlite_schema WHERE name = 'recipe_version'"));
    // Overwrite the page header of the recipe_version table's root page.
    test::writeBytes(file, std::string(64, '\xff'), (root - 1) * page_size);
    Database db = Database::open(file);
    EXPECT_FALSE(db.integrityCheck().empty());
    try {
        listRecipes(db);
        FAIL();
    } catch (const DatabaseError& e) {
        EXPECT_EQ(e.reason(), DatabaseError::Reason::Corrupt) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("restore it from a backup"), std::string::npos) << e.what();
    }
}

// A database written by a version-1 build (schema 0001 only) is brought to
// version 2 on open, keeping its rows; the new binder columns read as unset.
TEST(Migrations, Version1DatabaseMigratesToVersion2KeepingItsData) {
    TempDir dir;
    const auto file = dir / "v1.db";
    const auto& migrations = detail::builtInMigrations();
    ASSERT_EQ(migrations.size(), 2U);
    {
        detail::Connection connection(file, true);
        detail::migrate(connection, std::span(migrations).first(1));
        EXPECT_EQ(detail::userVersion(connection), 1);
    }
    ASSERT_EQ(rawExec(file,
                      "INSERT INTO spectrum (id, quantity, unit, wavelengths_nm, spectrum_values) VALUES "
                      "(1, 'refractive_index', '1', '[380]', '[1.49]'), (2, 'absorption_per_um', '1/µm', "
                      "'[380]', '[0]'); INSERT INTO ingredient (id, kind, name, density_g_cm3) VALUES "
                      "(1, 'binder', 'kept', 1.18); INSERT INTO binder VALUES (1, 1, 2);"),
              SQLITE_OK);
    {
        Database db = Database::open(file);
        EXPECT_EQ(db.schemaVersion(), 2);
        const auto kept = findIngredient(db, IngredientKind::Binder, "kept");
        ASSERT_TRUE(kept.has_value());
        EXPECT_EQ(kept->density_g_cm3, 1.18);
        EXPECT_FALSE(kept->solids_mass_fraction.has_value());
        EXPECT_EQ(std::get<Binder>(kept->data).refractive_index, Spectrum(1.49));
        EXPECT_TRUE(db.integrityCheck().empty());
    }
    EXPECT_EQ(rawQuery(file, "SELECT count(*) FROM pragma_table_info('spectrum') WHERE name = 'name'"), "1");
}

// The migration runner with a further, test-only step: what the next schema
// version will go through.
TEST(Migrations, OlderSchemaIsMigratedKeepingItsData) {
    TempDir dir;
    const auto file = dir / "old.db";
    const auto& current = detail::builtInMigrations();
    {
        detail::Connection connection(file, true);
        detail::migrate(connection, current);
        EXPECT_EQ(detail::userVersion(connection), 2);
    }
    ASSERT_EQ(rawExec(file, "INSERT INTO ingredient (kind, name) VALUES ('binder', 'kept')"), SQLITE_OK);

    std::vector<detail::Migration> next = current;
    next.push_back(
        {3, "0003_supplier.sql", "ALTER TABLE ingredient ADD COLUMN supplier TEXT NOT NULL DEFAULT 'n/a';"});
    {
        detail::Connection connection(file, true);
        EXPECT_EQ(detail::checkSchema(connection, next), 2);
        detail::migrate(connection, next);
        EXPECT_EQ(detail::userVersion(connection), 3);
    }
    EXPECT_EQ(rawQuery(file, "SELECT name || '/' || supplier FROM ingredient"), "kept/n/a");
    // This build knows version 2 only: the migrated file is now too new for it.
    expectRefused(file, DatabaseError::Reason::NewerSchema, "schema version 3");
}

TEST(Migrations, FailingStepIsRolledBackAndNamed) {
    TempDir dir;
    const auto file = dir / "fail.db";
    std::vector<detail::Migration> steps = detail::builtInMigrations();
    steps.push_back({3, "0003_broken.sql", "CREATE TABLE half_done (a); THIS IS NOT SQL;"});
    detail::Connection connection(file, true);
    try {
        detail::migrate(connection, steps);
        FAIL();
    } catch (const DatabaseError& e) {
        EXPECT_NE(std::string(e.what()).find("fail.db"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("from version 2 to 3 (0003_broken.sql)"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(detail::userVersion(connection), 2);  // steps 1 and 2 committed, step 3 undone
    EXPECT_EQ(rawQuery(file, "SELECT count(*) FROM sqlite_schema WHERE name = 'half_done'"), "0");
}

TEST(Migrations, EmptyVersionZeroFileIsUpgraded) {
    TempDir dir;
    const auto file = dir / "empty.db";
    test::writeBytes(file, "");  // a zero-byte file is an empty SQLite database
    Database db = Database::open(file);
    EXPECT_EQ(db.schemaVersion(), 2);
}

}  // namespace
}  // namespace paintlab::db
