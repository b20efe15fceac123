#include "json_guard.h"

#include "paintlab/engine/error.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <system_error>

namespace paintlab::detail {

namespace {

struct TextPosition {
    std::size_t line = 1;
    std::size_t column = 1;
};

TextPosition positionOf(std::string_view text, std::size_t byte) {
    TextPosition pos;
    const std::size_t end = std::min(byte, text.size());
    for (std::size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++pos.line;
            pos.column = 1;
        } else {
            ++pos.column;
        }
    }
    return pos;
}

// The last `"key":` before byte, so that "NaN" or a truncation is reported
// against the field the user was writing. Heuristic but only used for messages.
std::string lastKeyBefore(std::string_view text, std::size_t byte) {
    const std::size_t end = std::min(byte, text.size());
    std::size_t colon = text.rfind(':', end == 0 ? 0 : end - 1);
    while (colon != std::string_view::npos && colon > 0) {
        std::size_t q = colon;
        while (q > 0 &&
               (text[q - 1] == ' ' || text[q - 1] == '\t' || text[q - 1] == '\n' || text[q - 1] == '\r'))
            --q;
        if (q > 0 && text[q - 1] == '"') {
            const std::size_t open = text.rfind('"', q - 2 < q ? q - 2 : 0);
            if (open != std::string_view::npos && q - 1 > open && q - 1 - open <= 64)
                return std::string(text.substr(open + 1, q - 2 - open));
        }
        if (colon == 0) break;
        colon = text.rfind(':', colon - 1);
    }
    return {};
}

std::string tokenAt(std::string_view text, std::size_t byte) {
    if (byte >= text.size()) return {};
    std::size_t start = byte;
    // nlohmann reports the byte after the bad token; step back over it.
    while (start > 0 && std::isalnum(static_cast<unsigned char>(text[start - 1])) != 0) --start;
    std::size_t stop = start;
    while (
        stop < text.size() && stop - start < 24 &&
        (std::isalnum(static_cast<unsigned char>(text[stop])) != 0 || text[stop] == '-' || text[stop] == '.'))
        ++stop;
    return std::string(text.substr(start, stop - start));
}

}  // namespace

std::string readBoundedTextFile(const std::filesystem::path& path, std::size_t max_bytes) {
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(name, "", "file not found");
    if (std::filesystem::is_directory(path, ec)) throw InputError(name, "", "is a directory, not a file");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name, "", "cannot read file size: " + ec.message());
    if (size == 0) throw InputError(name, "", "file is empty");
    if (size > max_bytes)
        throw InputError(name, "",
                         "file is " + std::to_string(size) + " bytes; the limit for this kind of file is " +
                             std::to_string(max_bytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name, "", "cannot open file for reading");
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::size_t>(in.gcount()) != size)
        throw InputError(name, "", "file could not be read completely");
    return text;
}

nlohmann::json parseUntrustedJson(std::string_view text, const std::string& source, std::size_t max_depth) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) throw InputError(source, "", "file is empty (only white space)");
    if (text[first] != '{' && text[first] != '[')
        throw InputError(source, "", "not a JSON document (it should start with '{')");

    // The callback sees every nesting step; refusing deep documents keeps
    // memory and recursion bounded whatever the input.
    const nlohmann::json::parser_callback_t depth_guard = [&](int depth, nlohmann::json::parse_event_t,
                                                              nlohmann::json&) {
        if (depth > static_cast<int>(max_depth))
            throw InputError(source, "", "JSON nested deeper than " + std::to_string(max_depth) + " levels");
        return true;
    };
    try {
        return nlohmann::json::parse(text.begin(), text.end(), depth_guard);
    } catch (const nlohmann::json::parse_error& e) {
        const TextPosition pos = positionOf(text, e.byte == 0 ? 0 : e.byte - 1);
        const std::string key = lastKeyBefore(text, e.byte == 0 ? 0 : e.byte - 1);
        std::string what = e.byte >= text.size() ? "the file ends early (truncated JSON)" : "malformed JSON";
        const std::string token = tokenAt(text, e.byte == 0 ? 0 : e.byte - 1);
        if (token == "NaN" || token == "nan" || token == "Infinity" || token == "-Infinity" || token == "inf")
            what = "'" + token + "' is not a number JSON allows; every value must be finite";
        throw InputError(source, key.empty() ? std::string() : "near field '" + key + "'",
                         "line " + std::to_string(pos.line) + ", column " + std::to_string(pos.column) +
                             ": " + what);
    } catch (const nlohmann::json::out_of_range& e) {
        // A number too large for a double (1e999); nlohmann quotes the token, find it to name the field.
        const std::string message = e.what();
        const auto open = message.find('\'');
        const auto close = message.rfind('\'');
        const std::string token = open < close ? message.substr(open + 1, close - open - 1) : std::string();
        const std::size_t at = token.empty() ? std::string_view::npos : text.find(token);
        const std::string key = at == std::string_view::npos ? std::string() : lastKeyBefore(text, at);
        const TextPosition pos = positionOf(text, at == std::string_view::npos ? 0 : at);
        throw InputError(source, key.empty() ? std::string() : "near field '" + key + "'",
                         "line " + std::to_string(pos.line) + ", column " + std::to_string(pos.column) +
                             ": number '" + token + "' is too large to be finite");
    }
}

}  // namespace paintlab::detail
