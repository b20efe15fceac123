#pragma once
// The PaintLab database: one SQLite file holding ingredients, spectra,
// recipes with immutable versions, measurements and fits
// (shared/ARCHITECTURE.md, "Database"; docs/ARCHITECTURE.md, "Database").
//
// A Database is one connection: WAL journal (readers never block the
// writer and never see a half-written transaction), foreign keys on, a busy
// timeout, synchronous=FULL. Opening brings an older schema up to date with
// the ordered migrations (each in its own transaction) and refuses, without
// touching the file, a schema newer than this build knows. Every write made
// through the repository functions (ingredients.h, recipes.h) runs in one
// transaction: it is saved whole or not at all.
//
// One Database per thread: a connection is not shared between threads
// (open another one; SQLite's file locking coordinates them).

#include "paintlab/engine/error.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace paintlab::db {

// Every failure of the database names the file. reason() tells apart what
// the user can act on (a bad or newer file, a locked or read-only one, a full disk).
class DatabaseError : public Error {
public:
    enum class Reason {
        CannotOpen,    // missing, a folder, no permission to create
        NotADatabase,  // not an SQLite file, or an SQLite file of another program
        Corrupt,       // SQLite reports a malformed database image
        NewerSchema,   // written by a newer PaintLab; left untouched
        Busy,          // another connection holds the write lock longer than the busy timeout
        ReadOnly,      // the file (or its folder) cannot be written
        Full,          // disk full or file size limit
        Io,            // another I/O error
        Constraint,    // a write broke a rule of the schema (immutability, uniqueness, ...)
        Other,
    };

    DatabaseError(std::filesystem::path file, Reason reason, const std::string& message);

    const std::filesystem::path& file() const noexcept { return m_file; }
    Reason reason() const noexcept { return m_reason; }
    // True when the file given is at fault (not SQLite, corrupt, newer schema,
    // missing): the CLI reports it as bad input.
    bool isBadFile() const noexcept;

private:
    std::filesystem::path m_file;
    Reason m_reason;
};

struct OpenOptions {
    bool create = true;  // create the file (and its folder) if it does not exist
    // How long a write waits for another connection's write transaction
    // before failing with Reason::Busy.
    int busy_timeout_ms = 5000;
};

class Database {
public:
    // Opens (or creates) the database and migrates it to the latest schema.
    // Throws DatabaseError naming the file: cannot open or create it, not a
    // PaintLab database, corrupt, newer schema (the file is not altered),
    // locked during a migration, read-only but in need of a migration.
    static Database open(const std::filesystem::path& file, const OpenOptions& options = {});

    Database(Database&&) noexcept;
    Database& operator=(Database&&) noexcept;
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;
    ~Database();

    const std::filesystem::path& file() const noexcept;
    int schemaVersion() const;
    // The schema version this build writes (the number of migrations it knows).
    static int latestSchemaVersion();
    // True if the file could only be opened for reading (writes will fail with Reason::ReadOnly).
    bool isReadOnly() const;

    // PRAGMA integrity_check: empty if the file is sound, else SQLite's findings.
    std::vector<std::string> integrityCheck() const;

    // A consistent copy of the whole database into target (SQLite's online
    // backup; safe while other connections write). target must not exist.
    // Throws DatabaseError naming the file that failed.
    void backupTo(const std::filesystem::path& target) const;

    // The connection, for the repository functions (opaque outside src/).
    struct Impl;
    Impl& impl() const noexcept { return *m_impl; }

private:
    explicit Database(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

}  // namespace paintlab::db
