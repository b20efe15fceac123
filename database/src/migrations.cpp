// Schema version checks and the migration runner (migrations.h).

#include "migrations.h"

#include "embedded_files.h"

#include <string>

namespace paintlab::db::detail {

namespace {

int pragmaInt(const Connection& connection, const char* sql) {
    Statement statement(connection, sql);
    return statement.step() ? static_cast<int>(statement.integer(0)) : 0;
}

}  // namespace

const std::vector<Migration>& builtInMigrations() {
    static const std::vector<Migration> migrations = [] {
        std::vector<Migration> out;
        int version = 0;
        for (const auto& file : migrationFiles()) out.push_back({++version, file.name, file.text});
        return out;
    }();
    return migrations;
}

int userVersion(const Connection& connection) { return pragmaInt(connection, "PRAGMA user_version"); }

int checkSchema(const Connection& connection, std::span<const Migration> migrations) {
    using Reason = DatabaseError::Reason;
    // The first read of the file: an SQLite error here (not a database, encrypted) says what the file is.
    const int version = userVersion(connection);
    const int application_id = pragmaInt(connection, "PRAGMA application_id");
    const int known = migrations.empty() ? 0 : migrations.back().version;
    if (application_id != 0 && application_id != kApplicationId)
        throw DatabaseError(connection.file(), Reason::NotADatabase,
                            "an SQLite database of another program (application_id " +
                                std::to_string(application_id) + "), not a PaintLab database");
    if (version == 0 && application_id == 0) {
        // Version 0 is a new, empty file; tables there mean someone else's database.
        if (pragmaInt(connection, "SELECT count(*) FROM sqlite_schema") > 0)
            throw DatabaseError(connection.file(), Reason::NotADatabase,
                                "an SQLite database of another program (it has tables but no PaintLab "
                                "schema version), not a PaintLab database");
    }
    if (version > known)
        throw DatabaseError(connection.file(), Reason::NewerSchema,
                            "database schema version " + std::to_string(version) +
                                " is newer than this build of PaintLab supports (" + std::to_string(known) +
                                "); it was left unchanged. Open it with a newer PaintLab.");
    if (version < 0)
        throw DatabaseError(connection.file(), Reason::NotADatabase,
                            "negative schema version " + std::to_string(version));
    return version;
}

void migrate(const Connection& connection, std::span<const Migration> migrations) {
    for (const auto& step : migrations) {
        if (step.version <= userVersion(connection)) continue;
        if (connection.isReadOnly())
            throw DatabaseError(connection.file(), DatabaseError::Reason::ReadOnly,
                                "the database needs upgrading to schema version " +
                                    std::to_string(step.version) + " but the file is read-only");
        Transaction transaction(connection, Transaction::Mode::Write);
        // Another process may have run this step while we waited for the lock.
        if (step.version <= userVersion(connection)) continue;
        const int from = userVersion(connection);
        if (from != step.version - 1)
            throw DatabaseError(connection.file(), DatabaseError::Reason::Other,
                                "no migration from schema version " + std::to_string(from) + " to " +
                                    std::to_string(step.version));
        const std::string doing = "upgrading the schema from version " + std::to_string(from) + " to " +
                                  std::to_string(step.version) + " (" + step.name + ")";
        connection.exec(step.sql, doing);
        // PRAGMA takes no parameters; the version is an integer we produced.
        connection.exec("PRAGMA user_version = " + std::to_string(step.version), doing);
        transaction.commit();
    }
}

}  // namespace paintlab::db::detail
