#pragma once
// CSV as RFC 4180 writes it: comma-separated, a field with a comma, quote or
// line break is double-quoted and its quotes doubled, the first record is
// the header. The reader keeps each record's line number for error messages
// and refuses what a cut-off or hand-mangled file looks like (an unclosed
// quote, a record with more or fewer fields than the header). Numbers are
// read and written the same in every locale (std::from_chars, number_format.h).

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::io {

struct CsvRecord {
    std::size_t line = 0;  // 1-based line where the record starts
    std::vector<std::string> fields;
};

class CsvTable {
public:
    // Throws InputError naming source and the line: empty file, unclosed
    // quote, a record whose field count differs from the header's, an empty
    // or repeated column name. Blank lines are skipped; a UTF-8 BOM is dropped.
    static CsvTable parse(std::string_view text, const std::string& source);

    const std::string& source() const noexcept { return m_source; }
    const std::vector<std::string>& header() const noexcept { return m_header; }
    const std::vector<CsvRecord>& records() const noexcept { return m_records; }

    // The index of a column, if the header has it.
    std::optional<std::size_t> column(std::string_view name) const;
    // Throws InputError(source, "header", "missing column ...") unless every name is a column.
    void requireColumns(std::initializer_list<std::string_view> names) const;
    // Throws InputError naming the first column not in allowed.
    void allowOnlyColumns(const std::vector<std::string_view>& allowed) const;

    // The field of a record in the named column ("" when the column is absent).
    const std::string& field(const CsvRecord& record, std::string_view column) const;
    // A finite number, or nullopt for an empty field. Throws InputError
    // "line N, column C: 'x' is not a finite number".
    std::optional<double> number(const CsvRecord& record, std::string_view column) const;
    double requiredNumber(const CsvRecord& record, std::string_view column) const;
    // "line 12, column value"
    static std::string where(const CsvRecord& record, std::string_view column);

private:
    std::string m_source;
    std::size_t m_header_line = 0;
    std::vector<std::string> m_header;
    std::vector<CsvRecord> m_records;
};

// One field, quoted if it must be.
std::string csvField(std::string_view text);
// The shortest decimal text that reads back as the same double
// (NumberFormat::Shortest); "" for nullopt.
std::string csvNumber(double value);
std::string csvNumber(const std::optional<double>& value);
// Fields joined by commas, ended by "\n" (each is quoted here with csvField).
std::string csvLine(const std::vector<std::string>& fields);
// Fields already quoted (or known to need no quotes, as numbers) joined by
// commas, ended by "\n".
std::string csvJoin(const std::vector<std::string>& quoted_fields);

}  // namespace paintlab::io
