// Opening a PaintLab database: connection settings, schema checks and
// migrations, integrity check and online backup (database.h).

#include "paintlab/database/database.h"

#include "migrations.h"
#include "sqlite.h"

#include <sqlite3.h>

#include <system_error>

namespace paintlab::db {

namespace {

std::string composeMessage(const std::filesystem::path& file, const std::string& message) {
    std::string text = file.string();
    text.append(": ").append(message);
    return text;
}

}  // namespace

DatabaseError::DatabaseError(std::filesystem::path file, Reason reason, const std::string& message)
    : Error(composeMessage(file, message)), m_file(std::move(file)), m_reason(reason) {}

bool DatabaseError::isBadFile() const noexcept {
    return m_reason == Reason::CannotOpen || m_reason == Reason::NotADatabase ||
           m_reason == Reason::Corrupt || m_reason == Reason::NewerSchema;
}

Database::Database(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Database::Database(Database&&) noexcept = default;
Database& Database::operator=(Database&&) noexcept = default;
Database::~Database() = default;

Database Database::open(const std::filesystem::path& file, const OpenOptions& options) {
    using Reason = DatabaseError::Reason;
    std::error_code ec;
    const bool exists = std::filesystem::exists(file, ec);
    if (!exists && !options.create) throw DatabaseError(file, Reason::CannotOpen, "no such database file");
    if (exists && std::filesystem::is_directory(file, ec))
        throw DatabaseError(file, Reason::CannotOpen, "is a folder, not a database file");
    if (!exists && file.has_parent_path()) {
        std::filesystem::create_directories(file.parent_path(), ec);
        if (ec) throw DatabaseError(file, Reason::CannotOpen, "cannot create its folder: " + ec.message());
    }

    auto impl = std::make_unique<Impl>(file, options.create);
    impl->busy_timeout_ms = options.busy_timeout_ms;
    const detail::Connection& connection = impl->connection;
    sqlite3_busy_timeout(connection.handle(), options.busy_timeout_ms);
    // Foreign keys are per connection and off by default in SQLite.
    connection.exec("PRAGMA foreign_keys = ON", "enabling foreign keys");

    // Read-only checks first: a file we refuse must not be written, and
    // switching the journal mode writes the header.
    const auto& migrations = detail::builtInMigrations();
    detail::checkSchema(connection, migrations);

    if (!connection.isReadOnly()) {
        // WAL: readers see the last committed state while a writer works, and
        // a writer killed mid-transaction leaves nothing half visible.
        detail::Statement journal(connection, "PRAGMA journal_mode = WAL");
        if (journal.step() && journal.text(0) != "wal")
            throw DatabaseError(file, Reason::Other,
                                "cannot switch to WAL journal mode (got '" + journal.text(0) + "')");
    }
    // FULL: a committed transaction survives a power cut, not just a crash.
    connection.exec("PRAGMA synchronous = FULL", "setting synchronous mode");
    detail::migrate(connection, migrations);
    return Database(std::move(impl));
}

const std::filesystem::path& Database::file() const noexcept { return m_impl->connection.file(); }

int Database::schemaVersion() const { return detail::userVersion(m_impl->connection); }

int Database::latestSchemaVersion() { return static_cast<int>(detail::builtInMigrations().size()); }

bool Database::isReadOnly() const { return m_impl->connection.isReadOnly(); }

std::vector<std::string> Database::integrityCheck() const {
    std::vector<std::string> problems;
    try {
        detail::Statement check(m_impl->connection, "PRAGMA integrity_check");
        while (check.step()) {
            std::string line = check.text(0);
            if (line != "ok") problems.push_back(std::move(line));
        }
        detail::Statement keys(m_impl->connection, "PRAGMA foreign_key_check");
        while (keys.step())
            problems.push_back("foreign key violation in table " + keys.text(0) + ", row " +
                               std::to_string(keys.integer(1)));
    } catch (const DatabaseError& e) {
        // A file too damaged for the check to finish is its own finding.
        if (e.reason() != DatabaseError::Reason::Corrupt && e.reason() != DatabaseError::Reason::NotADatabase)
            throw;
        problems.emplace_back(e.what());
    }
    return problems;
}

void Database::backupTo(const std::filesystem::path& target) const {
    using Reason = DatabaseError::Reason;
    std::error_code ec;
    if (std::filesystem::exists(target, ec))
        throw DatabaseError(target, Reason::CannotOpen, "backup target already exists; not overwritten");
    detail::Connection destination(target, true);
    sqlite3_backup* backup =
        sqlite3_backup_init(destination.handle(), "main", m_impl->connection.handle(), "main");
    if (backup == nullptr) destination.fail(sqlite3_errcode(destination.handle()), "starting the backup");
    // One step copies every page; on a busy source it is retried inside the busy timeout.
    const int rc = sqlite3_backup_step(backup, -1);
    sqlite3_backup_finish(backup);
    if (rc != SQLITE_DONE) {
        destination.fail(rc, "copying the database to the backup");
    }
}

}  // namespace paintlab::db
