// RAII owners of SQLite handles and the result-code translation (sqlite.h).

#include "sqlite.h"

#include <sqlite3.h>

namespace paintlab::db::detail {

namespace {

using Reason = DatabaseError::Reason;

Reason reasonOf(int rc) {
    switch (rc & 0xff) {  // the primary code of an extended result code
    case SQLITE_CANTOPEN:
    case SQLITE_PERM:
    case SQLITE_AUTH:
        return Reason::CannotOpen;
    case SQLITE_NOTADB:
        return Reason::NotADatabase;
    case SQLITE_CORRUPT:
        return Reason::Corrupt;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
        return Reason::Busy;
    case SQLITE_READONLY:
        return Reason::ReadOnly;
    case SQLITE_FULL:
        return Reason::Full;
    case SQLITE_IOERR:
        return Reason::Io;
    case SQLITE_CONSTRAINT:
        return Reason::Constraint;
    default:
        return Reason::Other;
    }
}

// What the user should know, in words, beyond SQLite's own short message.
std::string explain(Reason reason) {
    switch (reason) {
    case Reason::CannotOpen:
        return "cannot open the file (missing folder or no permission)";
    case Reason::NotADatabase:
        return "not a PaintLab database (the file is not an SQLite database)";
    case Reason::Corrupt:
        return "the database file is corrupt; restore it from a backup";
    case Reason::Busy:
        return "the database is locked by another program or connection; try again later";
    case Reason::ReadOnly:
        return "the database is read-only (file or folder permissions)";
    case Reason::Full:
        return "the disk is full or the file size limit was reached";
    case Reason::Io:
        return "input/output error (disk full, file size limit or a failing disk)";
    default:
        return {};
    }
}

}  // namespace

Connection::Connection(const std::filesystem::path& file, bool create) : m_file(file) {
    int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX;
    if (create) flags |= SQLITE_OPEN_CREATE;
    const int rc = sqlite3_open_v2(file.c_str(), &m_db, flags, nullptr);
    if (rc != SQLITE_OK) {
        std::string detail = m_db != nullptr ? sqlite3_errmsg(m_db) : sqlite3_errstr(rc);
        sqlite3_close(m_db);
        m_db = nullptr;
        throw DatabaseError(file, reasonOf(rc), "cannot open: " + detail);
    }
    sqlite3_extended_result_codes(m_db, 1);
}

Connection::~Connection() {
    // Every Statement is finalised before its Connection (they are scoped
    // inside its users), so close cannot report SQLITE_BUSY here.
    sqlite3_close(m_db);
}

void Connection::exec(std::string_view sql, std::string_view doing) const {
    const std::string text(sql);
    const int rc = sqlite3_exec(m_db, text.c_str(), nullptr, nullptr, nullptr);
    if (rc != SQLITE_OK) fail(rc, doing);
}

std::int64_t Connection::lastInsertId() const noexcept { return sqlite3_last_insert_rowid(m_db); }

std::int64_t Connection::changes() const noexcept { return sqlite3_changes64(m_db); }

bool Connection::isReadOnly() const noexcept { return sqlite3_db_readonly(m_db, "main") == 1; }

void Connection::fail(int rc, std::string_view doing) const {
    const Reason reason = reasonOf(rc);
    std::string message(doing);
    message.append(": ");
    const std::string words = explain(reason);
    if (!words.empty()) message.append(words).append(" (SQLite: ");
    message.append(sqlite3_errmsg(m_db));
    if (!words.empty()) message.append(")");
    throw DatabaseError(m_file, reason, message);
}

Statement::Statement(const Connection& connection, std::string_view sql)
    : m_connection(connection), m_sql(sql) {
    const int rc = sqlite3_prepare_v2(connection.handle(), m_sql.data(), static_cast<int>(m_sql.size()),
                                      &m_stmt, nullptr);
    if (rc != SQLITE_OK) connection.fail(rc, "preparing a query");
}

Statement::~Statement() { sqlite3_finalize(m_stmt); }

Statement& Statement::bind(int index, std::string_view text) {
    // SQLITE_TRANSIENT: SQLite copies the text, so the caller's buffer may go.
    const int rc =
        sqlite3_bind_text64(m_stmt, index, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8);
    if (rc != SQLITE_OK) m_connection.fail(rc, "binding a query parameter");
    return *this;
}

Statement& Statement::bind(int index, double value) {
    const int rc = sqlite3_bind_double(m_stmt, index, value);
    if (rc != SQLITE_OK) m_connection.fail(rc, "binding a query parameter");
    return *this;
}

Statement& Statement::bind(int index, std::int64_t value) {
    const int rc = sqlite3_bind_int64(m_stmt, index, value);
    if (rc != SQLITE_OK) m_connection.fail(rc, "binding a query parameter");
    return *this;
}

Statement& Statement::bind(int index, const std::optional<double>& value) {
    return value ? bind(index, *value) : bindNull(index);
}

Statement& Statement::bind(int index, const std::optional<std::int64_t>& value) {
    return value ? bind(index, *value) : bindNull(index);
}

Statement& Statement::bindNull(int index) {
    const int rc = sqlite3_bind_null(m_stmt, index);
    if (rc != SQLITE_OK) m_connection.fail(rc, "binding a query parameter");
    return *this;
}

bool Statement::step() {
    const int rc = sqlite3_step(m_stmt);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    m_connection.fail(rc, "running a query");
}

void Statement::run() {
    while (step()) {}
}

void Statement::reset() {
    sqlite3_reset(m_stmt);
    sqlite3_clear_bindings(m_stmt);
}

int Statement::columnCount() const { return sqlite3_column_count(m_stmt); }

bool Statement::isNull(int column) const { return sqlite3_column_type(m_stmt, column) == SQLITE_NULL; }

std::string Statement::text(int column) const {
    const unsigned char* data = sqlite3_column_text(m_stmt, column);
    const int size = sqlite3_column_bytes(m_stmt, column);
    if (data == nullptr) return {};
    // SQLite hands out unsigned char; the bytes are UTF-8 text.
    return {reinterpret_cast<const char*>(data), static_cast<std::size_t>(size)};  // NOLINT
}

double Statement::real(int column) const { return sqlite3_column_double(m_stmt, column); }

std::int64_t Statement::integer(int column) const { return sqlite3_column_int64(m_stmt, column); }

std::optional<double> Statement::optionalReal(int column) const {
    if (isNull(column)) return std::nullopt;
    return real(column);
}

std::optional<std::int64_t> Statement::optionalInteger(int column) const {
    if (isNull(column)) return std::nullopt;
    return integer(column);
}

Transaction::Transaction(const Connection& connection, Mode mode) : m_connection(connection) {
    m_nested = sqlite3_get_autocommit(connection.handle()) == 0;
    if (m_nested) {
        connection.exec("SAVEPOINT paintlab_nested", "starting a nested transaction");
        m_open = true;
        return;
    }
    connection.exec(mode == Mode::Write ? "BEGIN IMMEDIATE" : "BEGIN",
                    mode == Mode::Write ? "starting a write transaction" : "starting a read transaction");
    m_open = true;
}

Transaction::~Transaction() {
    // Not committed (an exception is on its way): undo everything. A failed
    // ROLLBACK means SQLite already rolled back (e.g. after SQLITE_FULL).
    if (!m_open) return;
    const char* undo = m_nested ? "ROLLBACK TO paintlab_nested; RELEASE paintlab_nested" : "ROLLBACK";
    sqlite3_exec(m_connection.handle(), undo, nullptr, nullptr, nullptr);
}

void Transaction::commit() {
    m_connection.exec(m_nested ? "RELEASE paintlab_nested" : "COMMIT", "committing");
    m_open = false;
}

}  // namespace paintlab::db::detail
