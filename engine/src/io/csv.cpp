// RFC 4180 CSV reader and writer (io/csv.h).

#include "paintlab/engine/io/csv.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"

#include <charconv>
#include <cmath>
#include <set>

namespace paintlab::io {

namespace {

std::string lineText(std::size_t line) { return "line " + std::to_string(line); }

}  // namespace

CsvTable CsvTable::parse(std::string_view text, const std::string& source) {
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    std::vector<CsvRecord> records;
    std::size_t line = 1;
    std::size_t i = 0;
    while (i < text.size()) {
        CsvRecord record;
        record.line = line;
        std::string field;
        bool record_done = false;
        bool any_content = false;
        while (!record_done) {
            if (i < text.size() && text[i] == '"') {
                // A quoted field: up to the closing quote; "" is one quote.
                const std::size_t opened_line = line;
                ++i;
                bool closed = false;
                while (i < text.size()) {
                    const char c = text[i++];
                    if (c == '"') {
                        if (i < text.size() && text[i] == '"') {
                            field.push_back('"');
                            ++i;
                        } else {
                            closed = true;
                            break;
                        }
                    } else {
                        if (c == '\n') ++line;
                        field.push_back(c);
                    }
                }
                if (!closed)
                    throw InputError(source, lineText(opened_line),
                                     "a quoted field is never closed (truncated file?)");
                any_content = true;
                if (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r')
                    throw InputError(source, lineText(line), "text after a closing quote");
            }
            while (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r') {
                if (text[i] == '"')
                    throw InputError(source, lineText(line), "a quote inside an unquoted field");
                field.push_back(text[i++]);
                any_content = true;
            }
            record.fields.push_back(std::move(field));
            field.clear();
            if (i < text.size() && text[i] == ',') {
                ++i;
                any_content = true;
                continue;
            }
            // End of record: \n, \r\n or the end of the text.
            if (i < text.size() && text[i] == '\r') ++i;
            if (i < text.size() && text[i] == '\n') ++i;
            ++line;
            record_done = true;
        }
        if (any_content) records.push_back(std::move(record));
    }
    if (records.empty()) throw InputError(source, "", "the file is empty: no header line");

    CsvTable table;
    table.m_source = source;
    table.m_header_line = records.front().line;
    table.m_header = std::move(records.front().fields);
    std::set<std::string> seen;
    for (const auto& name : table.m_header) {
        if (name.empty()) throw InputError(source, lineText(table.m_header_line), "a column has no name");
        if (!seen.insert(name).second)
            throw InputError(source, lineText(table.m_header_line), "column '" + name + "' appears twice");
    }
    for (std::size_t r = 1; r < records.size(); ++r) {
        if (records[r].fields.size() != table.m_header.size())
            throw InputError(source, lineText(records[r].line),
                             std::to_string(records[r].fields.size()) + " fields where the header has " +
                                 std::to_string(table.m_header.size()) +
                                 (r + 1 == records.size() ? " (truncated file?)" : ""));
        table.m_records.push_back(std::move(records[r]));
    }
    return table;
}

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
    for (std::size_t i = 0; i < m_header.size(); ++i)
        if (m_header[i] == name) return i;
    return std::nullopt;
}

void CsvTable::requireColumns(std::initializer_list<std::string_view> names) const {
    for (const auto name : names)
        if (!column(name))
            throw InputError(m_source, lineText(m_header_line), "missing column '" + std::string(name) + "'");
}

void CsvTable::allowOnlyColumns(const std::vector<std::string_view>& allowed) const {
    for (const auto& name : m_header) {
        bool known = false;
        for (const auto a : allowed) known = known || a == name;
        if (!known) throw InputError(m_source, lineText(m_header_line), "unknown column '" + name + "'");
    }
}

const std::string& CsvTable::field(const CsvRecord& record, std::string_view column_name) const {
    static const std::string kEmpty;
    const auto index = column(column_name);
    return index ? record.fields[*index] : kEmpty;
}

std::string CsvTable::where(const CsvRecord& record, std::string_view column_name) {
    return lineText(record.line) + ", column " + std::string(column_name);
}

std::optional<double> CsvTable::number(const CsvRecord& record, std::string_view column_name) const {
    std::string_view text = field(record, column_name);
    while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    if (text.empty()) return std::nullopt;
    if (text.front() == '+') text.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        throw InputError(m_source, where(record, column_name),
                         "'" + field(record, column_name) + "' is not a finite number");
    return value;
}

double CsvTable::requiredNumber(const CsvRecord& record, std::string_view column_name) const {
    const auto value = number(record, column_name);
    if (!value) throw InputError(m_source, where(record, column_name), "empty; a number is required");
    return *value;
}

std::string csvField(std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos && !text.starts_with(' ') &&
        !text.ends_with(' '))
        return std::string(text);
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"') out.push_back('"');
        out.push_back(c);
    }
    out.push_back('"');
    return out;
}

std::string csvNumber(double value) { return formatNumber(value, NumberFormat::Shortest); }

std::string csvNumber(const std::optional<double>& value) {
    return value ? csvNumber(*value) : std::string();
}

std::string csvJoin(const std::vector<std::string>& quoted_fields) {
    std::string out;
    for (std::size_t i = 0; i < quoted_fields.size(); ++i) {
        if (i > 0) out.push_back(',');
        out += quoted_fields[i];
    }
    out.push_back('\n');
    return out;
}

std::string csvLine(const std::vector<std::string>& fields) {
    std::vector<std::string> quoted;
    quoted.reserve(fields.size());
    for (const auto& field : fields) quoted.push_back(csvField(field));
    return csvJoin(quoted);
}

}  // namespace paintlab::io
