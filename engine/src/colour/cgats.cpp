#include "colour/cgats.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/cgats.h"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

namespace paintlab::cgats {
namespace {

// colord's largest table (CIE-A.sp, 531 bands) is about 10 kB; anything far
// bigger is not one of these files, and must not be read whole into memory.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{4} * 1024 * 1024;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
    throw Error(file.string() + ": " + message);
}

[[noreturn]] void failAt(const std::filesystem::path& file, std::size_t line, const std::string& message) {
    throw Error(file.string() + ":" + std::to_string(line) + ": " + message);
}

std::string readWholeFile(const std::filesystem::path& file) {
    std::error_code error;
    const auto status = std::filesystem::status(file, error);
    if (error) fail(file, "cannot read CIE table: " + error.message());
    if (!std::filesystem::is_regular_file(status)) fail(file, "cannot read CIE table: not a regular file");
    const auto size = std::filesystem::file_size(file, error);
    if (error) fail(file, "cannot read CIE table: " + error.message());
    if (size > kMaxFileBytes) fail(file, "is " + std::to_string(size) + " bytes, too big for a CIE table");
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot open CIE table");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) fail(file, "read error");
    return text.str();
}

// Strict parse: the whole token must be a number (from_chars is locale-independent).
bool parseDouble(std::string_view text, double& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const char* const end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

// A header keyword's value; the table comes from lcms2 (io/cgats.h).
std::string requireKeyword(const std::filesystem::path& file, const io::CgatsTable& parsed,
                           std::string_view name) {
    const auto found = parsed.properties.find(name);
    if (found == parsed.properties.end()) fail(file, "header has no " + std::string(name));
    return found->second;
}

double requireNumber(const std::filesystem::path& file, const io::CgatsTable& parsed, std::string_view name) {
    const std::string text = requireKeyword(file, parsed, name);
    double value = 0.0;
    if (!parseDouble(text, value) || !std::isfinite(value))
        fail(file, std::string(name) + " '" + text + "' is not a finite number");
    return value;
}

std::size_t requireCount(const std::filesystem::path& file, const io::CgatsTable& parsed,
                         std::string_view name) {
    const std::string text = requireKeyword(file, parsed, name);
    std::size_t value = 0;
    const char* const end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value == 0)
        fail(file, std::string(name) + " '" + text + "' is not a positive integer");
    return value;
}

// CGATS is text; a control byte means a binary or damaged file, and must not
// end up inside an error message as a "keyword".
void requireText(const std::filesystem::path& file, const std::string& text) {
    std::size_t line = 1;
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '\n')
            ++line;
        else if ((byte < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') || byte == 0x7f)
            failAt(file, line, "is not a text file (control byte " + std::to_string(byte) + ")");
    }
    if (text.find_first_not_of(" \t\r\n\v\f") == std::string::npos) fail(file, "is empty");
}

}  // namespace

SpectralTable readSpectralTable(const std::filesystem::path& file, std::size_t expected_sets) {
    const std::string text = readWholeFile(file);
    requireText(file, text);
    io::CgatsTable parsed;
    try {
        parsed = io::parseCgats(text, file.string());
    } catch (const InputError& e) {
        throw Error(e.what());
    }

    // The grid comes from these keywords, not from the field names: colord's
    // names are not a reliable encoding (CIE-A.sp calls its 300 nm field SPEC_300000).
    const double start_nm = requireNumber(file, parsed, "SPECTRAL_START_NM");
    const double end_nm = requireNumber(file, parsed, "SPECTRAL_END_NM");
    const std::size_t bands = requireCount(file, parsed, "SPECTRAL_BANDS");
    const std::size_t fields = requireCount(file, parsed, "NUMBER_OF_FIELDS");
    const std::size_t sets = requireCount(file, parsed, "NUMBER_OF_SETS");
    if (bands < 2 || !(end_nm > start_nm))
        fail(file, "spectral range " + std::to_string(start_nm) + "-" + std::to_string(end_nm) + " nm in " +
                       std::to_string(bands) + " bands is not a range");
    if (fields != bands)
        fail(file, "NUMBER_OF_FIELDS " + std::to_string(fields) + " differs from SPECTRAL_BANDS " +
                       std::to_string(bands));
    if (parsed.columns.size() != fields)
        fail(file, "data format lists " + std::to_string(parsed.columns.size()) + " fields, header says " +
                       std::to_string(fields));
    for (const std::string& name : parsed.columns)
        if (!name.starts_with("SPEC_")) fail(file, "field '" + name + "' is not a spectral (SPEC_) field");
    if (sets != expected_sets)
        fail(file, "has " + std::to_string(sets) + " data sets, expected " + std::to_string(expected_sets));
    if (parsed.valueCount() != fields * sets || parsed.rows.size() != sets)
        fail(file, "data block has " + std::to_string(parsed.valueCount()) + " values, expected " +
                       std::to_string(sets) + " sets of " + std::to_string(fields) + " (truncated?)");

    SpectralTable table;
    table.wavelengths_nm.resize(bands);
    // start + span * i / (bands - 1) is exact at both ends and, for whole-nm
    // steps, at every sample (470 * i / 94 == 5 * i exactly).
    for (std::size_t i = 0; i < bands; ++i)
        table.wavelengths_nm[i] =
            start_nm + (end_nm - start_nm) * static_cast<double>(i) / static_cast<double>(bands - 1);
    table.sets.assign(sets, std::vector<double>(fields));
    for (std::size_t set = 0; set < sets; ++set)
        for (std::size_t k = 0; k < fields; ++k) {
            const std::string& cell = parsed.rows[set][k];
            double value = 0.0;
            const bool finite = parseDouble(cell, value) && std::isfinite(value);
            if (finite && value >= 0.0) {
                table.sets[set][k] = value;
                continue;
            }
            std::string message = "data set ";
            message.append(std::to_string(set + 1)).append(", ").append(parsed.columns[k]);
            if (finite)
                message.append(": negative value ").append(cell).append(" in a spectral table");
            else
                message.append(": '").append(cell).append("' is not a finite number");
            fail(file, message);
        }
    return table;
}

}  // namespace paintlab::cgats
