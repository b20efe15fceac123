#pragma once
// Schema versions and forward migrations. The schema version is SQLite's
// PRAGMA user_version; migration i (1-based) brings version i - 1 to i, in
// its own write transaction together with the new user_version, so a crash
// or an error leaves the previous version intact. A file whose version is
// newer than the last migration is refused and never written.

#include "sqlite.h"

#include <span>
#include <string>
#include <vector>

namespace paintlab::db::detail {

// "PLDB": PRAGMA application_id of every PaintLab database (set by migration 1).
inline constexpr int kApplicationId = 0x504c4442;

struct Migration {
    int version = 0;   // the schema version after this step
    std::string name;  // "0001_initial.sql"
    std::string sql;
};

// The migrations compiled into this build (database/migrations/*.sql), in order.
const std::vector<Migration>& builtInMigrations();

int userVersion(const Connection& connection);

// Refuses files that are not PaintLab databases or are newer than
// migrations.back().version (DatabaseError naming the file and both
// versions), without writing anything. Returns the file's schema version.
int checkSchema(const Connection& connection, std::span<const Migration> migrations);

// Runs every migration newer than the file's version, each in a write
// transaction. Throws DatabaseError naming the file and the failing step;
// the steps already committed stay.
void migrate(const Connection& connection, std::span<const Migration> migrations);

}  // namespace paintlab::db::detail
