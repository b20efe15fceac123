#pragma once
// The only place that touches the SQLite C API's lifetimes: RAII owners for
// a connection and a prepared statement, a transaction guard, and the
// translation of SQLite result codes into DatabaseError naming the file.
// Private to the database library (never included by a public header).

#include "paintlab/database/database.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace paintlab::db::detail {

class Connection {
public:
    // Throws DatabaseError(file, CannotOpen, ...) if SQLite cannot open it.
    Connection(const std::filesystem::path& file, bool create);
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;
    ~Connection();

    sqlite3* handle() const noexcept { return m_db; }
    const std::filesystem::path& file() const noexcept { return m_file; }

    // Runs SQL without results (may hold several statements). Throws DatabaseError.
    void exec(std::string_view sql, std::string_view doing) const;
    std::int64_t lastInsertId() const noexcept;
    // Rows changed by the last INSERT, UPDATE or DELETE.
    std::int64_t changes() const noexcept;
    bool isReadOnly() const noexcept;

    // Throws DatabaseError for result code rc, with SQLite's message.
    [[noreturn]] void fail(int rc, std::string_view doing) const;

private:
    sqlite3* m_db = nullptr;
    std::filesystem::path m_file;
};

class Statement {
public:
    Statement(const Connection& connection, std::string_view sql);
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    ~Statement();

    // Parameters are 1-based, as in SQLite; they return *this for chaining.
    Statement& bind(int index, std::string_view text);
    Statement& bind(int index, double value);
    Statement& bind(int index, std::int64_t value);
    Statement& bind(int index, int value) { return bind(index, std::int64_t{value}); }
    Statement& bind(int index, const std::optional<double>& value);
    Statement& bind(int index, const std::optional<std::int64_t>& value);
    Statement& bindNull(int index);

    // Advances to the next row: true if there is one, false when done. Throws DatabaseError.
    bool step();
    // Runs a statement that returns no row.
    void run();
    void reset();

    // Columns are 0-based, as in SQLite.
    int columnCount() const;
    bool isNull(int column) const;
    std::string text(int column) const;
    double real(int column) const;
    std::int64_t integer(int column) const;
    std::optional<double> optionalReal(int column) const;
    std::optional<std::int64_t> optionalInteger(int column) const;

private:
    const Connection& m_connection;
    sqlite3_stmt* m_stmt = nullptr;
    std::string m_sql;  // for error messages
};

// BEGIN IMMEDIATE (Write: takes the write lock at once, so two writers never
// deadlock halfway) or BEGIN (Read: one consistent snapshot); rolls back
// unless commit() was called. Inside another transaction it is a SAVEPOINT,
// so repository functions compose into one larger transaction.
class Transaction {
public:
    enum class Mode { Read, Write };
    Transaction(const Connection& connection, Mode mode);
    Transaction(const Transaction&) = delete;
    Transaction& operator=(const Transaction&) = delete;
    ~Transaction();
    void commit();

private:
    const Connection& m_connection;
    bool m_open = false;
    bool m_nested = false;
};

}  // namespace paintlab::db::detail

// What Database::Impl holds: the connection and its options.
struct paintlab::db::Database::Impl {
    Impl(const std::filesystem::path& file, bool create) : connection(file, create) {}
    detail::Connection connection;
    int busy_timeout_ms = 5000;
};
