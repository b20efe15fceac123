#include "colour/cgats.h"

#include "paintlab/engine/error.h"

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

struct Token {
    std::string text;
    std::size_t line = 0;
};

struct Keyword {
    std::string value;
    std::size_t line = 0;
};

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

// Splits one line into whitespace-separated tokens; a double-quoted string is
// one token, and '#' outside quotes starts a comment (CGATS.17).
std::vector<std::string> splitLine(std::string_view line) {
    std::vector<std::string> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
            ++i;
        } else if (c == '#') {
            break;
        } else if (c == '"') {
            const std::size_t close = line.find('"', i + 1);
            const std::size_t end = close == std::string_view::npos ? line.size() : close;
            tokens.emplace_back(line.substr(i + 1, end - i - 1));
            i = end + 1;
        } else {
            std::size_t end = i;
            while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r' &&
                   line[end] != '#')
                ++end;
            tokens.emplace_back(line.substr(i, end - i));
            i = end;
        }
    }
    return tokens;
}

bool isReserved(std::string_view word) {
    return word == "BEGIN_DATA_FORMAT" || word == "END_DATA_FORMAT" || word == "BEGIN_DATA" ||
           word == "END_DATA";
}

// Strict parse: the whole token must be a number (from_chars is locale-independent).
bool parseDouble(std::string_view text, double& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const char* const end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

struct ParsedFile {
    std::map<std::string, Keyword, std::less<>> keywords;
    std::vector<Token> fieldNames;
    std::vector<Token> values;
};

ParsedFile parse(const std::filesystem::path& file, const std::string& text) {
    enum class State { Identifier, Header, Format, Data, Done };
    State state = State::Identifier;
    ParsedFile parsed;
    bool sawFormat = false;
    std::size_t lineNumber = 0;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        std::size_t newline = text.find('\n', begin);
        if (newline == std::string::npos) newline = text.size();
        ++lineNumber;
        const std::string_view line = std::string_view(text).substr(begin, newline - begin);
        // CGATS is text; a control byte means a binary or damaged file, and
        // must not end up inside an error message as a "keyword".
        for (const char c : line) {
            const auto byte = static_cast<unsigned char>(c);
            if ((byte < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') || byte == 0x7f)
                failAt(file, lineNumber, "is not a text file (control byte " + std::to_string(byte) + ")");
        }
        const auto tokens = splitLine(line);
        begin = newline + 1;
        if (tokens.empty()) continue;
        switch (state) {
        case State::Identifier:
            // The first line names the file type ("CMF", "SPECT", "CGATS.17", ...).
            if (tokens.size() != 1 || isReserved(tokens.front()))
                failAt(file, lineNumber, "does not start with a CGATS file identifier line");
            state = State::Header;
            break;
        case State::Header:
            if (tokens.front() == "BEGIN_DATA_FORMAT") {
                if (sawFormat) failAt(file, lineNumber, "second BEGIN_DATA_FORMAT block");
                sawFormat = true;
                state = State::Format;
                for (std::size_t t = 1; t < tokens.size(); ++t)
                    parsed.fieldNames.push_back({tokens[t], lineNumber});
            } else if (tokens.front() == "BEGIN_DATA") {
                if (!sawFormat) failAt(file, lineNumber, "BEGIN_DATA before any BEGIN_DATA_FORMAT block");
                state = State::Data;
                for (std::size_t t = 1; t < tokens.size(); ++t)
                    parsed.values.push_back({tokens[t], lineNumber});
            } else if (isReserved(tokens.front())) {
                failAt(file, lineNumber, "unexpected " + tokens.front());
            } else {
                // KEYWORD value; a keyword given twice is a sign of a damaged or merged file.
                Keyword keyword{tokens.size() > 1 ? tokens[1] : std::string(), lineNumber};
                if (!parsed.keywords.emplace(tokens.front(), std::move(keyword)).second)
                    failAt(file, lineNumber, "keyword " + tokens.front() + " given twice");
            }
            break;
        case State::Format:
        case State::Data: {
            const bool format = state == State::Format;
            for (const auto& token : tokens) {
                if (state != (format ? State::Format : State::Data))
                    failAt(file, lineNumber,
                           "unexpected '" + token + "' after " + (format ? "END_DATA_FORMAT" : "END_DATA"));
                if (token == (format ? "END_DATA_FORMAT" : "END_DATA"))
                    state = format ? State::Header : State::Done;
                else if (isReserved(token))
                    failAt(file, lineNumber, "unexpected " + token);
                else
                    (format ? parsed.fieldNames : parsed.values).push_back({token, lineNumber});
            }
            break;
        }
        case State::Done:
            // These files hold one table; anything after it means a damaged or concatenated file.
            failAt(file, lineNumber, "unexpected content after END_DATA");
        }
    }
    switch (state) {
    case State::Identifier:
        fail(file, "is empty");
    case State::Header:
        fail(file, "has no BEGIN_DATA block (truncated?)");
    case State::Format:
        fail(file, "ends inside the data format block: no END_DATA_FORMAT (truncated?)");
    case State::Data:
        fail(file, "ends inside the data block: no END_DATA (truncated?)");
    case State::Done:
        break;
    }
    return parsed;
}

const Keyword& requireKeyword(const std::filesystem::path& file, const ParsedFile& parsed,
                              std::string_view name) {
    const auto found = parsed.keywords.find(name);
    if (found == parsed.keywords.end()) fail(file, "header has no " + std::string(name));
    return found->second;
}

double requireNumber(const std::filesystem::path& file, const ParsedFile& parsed, std::string_view name) {
    const Keyword& keyword = requireKeyword(file, parsed, name);
    double value = 0.0;
    if (!parseDouble(keyword.value, value) || !std::isfinite(value))
        failAt(file, keyword.line, std::string(name) + " '" + keyword.value + "' is not a finite number");
    return value;
}

std::size_t requireCount(const std::filesystem::path& file, const ParsedFile& parsed, std::string_view name) {
    const Keyword& keyword = requireKeyword(file, parsed, name);
    std::size_t value = 0;
    const char* const end = keyword.value.data() + keyword.value.size();
    const auto [ptr, ec] = std::from_chars(keyword.value.data(), end, value);
    if (ec != std::errc() || ptr != end || value == 0)
        failAt(file, keyword.line, std::string(name) + " '" + keyword.value + "' is not a positive integer");
    return value;
}

}  // namespace

SpectralTable readSpectralTable(const std::filesystem::path& file, std::size_t expected_sets) {
    const ParsedFile parsed = parse(file, readWholeFile(file));

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
    if (parsed.fieldNames.size() != fields)
        fail(file, "data format lists " + std::to_string(parsed.fieldNames.size()) + " fields, header says " +
                       std::to_string(fields));
    for (const Token& name : parsed.fieldNames)
        if (name.text.rfind("SPEC_", 0) != 0)
            failAt(file, name.line, "field '" + name.text + "' is not a spectral (SPEC_) field");
    if (sets != expected_sets)
        fail(file, "has " + std::to_string(sets) + " data sets, expected " + std::to_string(expected_sets));
    if (parsed.values.size() != fields * sets)
        fail(file, "data block has " + std::to_string(parsed.values.size()) + " values, expected " +
                       std::to_string(sets) + " sets of " + std::to_string(fields) + " (truncated?)");

    SpectralTable table;
    table.wavelengths_nm.resize(bands);
    // start + span * i / (bands - 1) is exact at both ends and, for whole-nm
    // steps, at every sample (470 * i / 94 == 5 * i exactly).
    for (std::size_t i = 0; i < bands; ++i)
        table.wavelengths_nm[i] =
            start_nm + (end_nm - start_nm) * static_cast<double>(i) / static_cast<double>(bands - 1);
    table.sets.assign(sets, std::vector<double>(fields));
    for (std::size_t k = 0; k < parsed.values.size(); ++k) {
        const Token& token = parsed.values[k];
        double value = 0.0;
        if (!parseDouble(token.text, value) || !std::isfinite(value))
            failAt(file, token.line, "'" + token.text + "' is not a finite number");
        if (value < 0.0) failAt(file, token.line, "negative value " + token.text + " in a spectral table");
        table.sets[k / fields][k % fields] = value;
    }
    return table;
}

}  // namespace paintlab::cgats
