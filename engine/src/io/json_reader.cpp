#include "json_reader.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_paths.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <system_error>

namespace paintlab::jsonio {

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

std::string typeName(const nlohmann::json& value) {
    if (value.is_number()) return "a number";
    return std::string("a") + (value.is_object() ? "n " : " ") + value.type_name();
}

ObjectReader::ObjectReader(const nlohmann::json& object, std::string path, const std::string& source)
    : m_object(object), m_path(std::move(path)), m_source(source) {
    if (!m_object.is_object()) fail("", "expected a JSON object, found " + typeName(m_object));
}

void ObjectReader::fail(std::string_view key, const std::string& message) const {
    throw InputError(m_source, key.empty() ? m_path : fieldPath(key), message);
}

const nlohmann::json* ObjectReader::find(std::string_view key) {
    m_known.emplace_back(key);
    const auto it = m_object.find(key);
    return it == m_object.end() ? nullptr : &*it;
}

const nlohmann::json& ObjectReader::require(std::string_view key, std::string_view what) {
    const nlohmann::json* value = find(key);
    if (value == nullptr)
        fail(key, "missing required field '" + std::string(key) + "' (" + std::string(what) + ")");
    return *value;
}

std::string ObjectReader::string(std::string_view key, bool required) {
    const nlohmann::json* value = required ? &require(key, "text") : find(key);
    if (value == nullptr) return {};
    if (!value->is_string()) fail(key, "expected text, found " + typeName(*value));
    return value->get<std::string>();
}

double ObjectReader::number(std::string_view key, const nlohmann::json& value) const {
    if (!value.is_number()) fail(key, "expected a number, found " + typeName(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(key, "value is not a finite number");
    return x;
}

std::optional<double> ObjectReader::optionalNumber(std::string_view key) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) return std::nullopt;
    return number(key, *value);
}

std::vector<double> ObjectReader::numbers(std::string_view key, std::size_t min_entries) {
    std::vector<double> out = numberArray(key, require(key, "an array of numbers"));
    if (out.size() < min_entries)
        fail(key, "expected at least " + std::to_string(min_entries) + " numbers, found " +
                      std::to_string(out.size()));
    return out;
}

double ObjectReader::numberIn(std::string_view key, double lo, double hi, std::optional<double> fallback,
                              bool lo_exclusive) {
    const nlohmann::json* value = fallback ? find(key) : &require(key, "a number");
    const double x = value == nullptr ? *fallback : number(key, *value);
    if (x < lo || x > hi || (lo_exclusive && x == lo)) {
        std::string message = "must lie in ";
        message.append(lo_exclusive ? "(" : "[").append(std::to_string(lo)).append(", ");
        message.append(std::to_string(hi)).append("], found ").append(std::to_string(x));
        fail(key, message);
    }
    return x;
}

int ObjectReader::integerIn(std::string_view key, int lo, int hi, std::optional<int> fallback) {
    const double x = numberIn(key, lo, hi, fallback ? std::optional<double>(*fallback) : std::nullopt);
    if (x != std::floor(x)) fail(key, "must be a whole number, found " + std::to_string(x));
    return static_cast<int>(x);
}

std::vector<double> ObjectReader::numberArray(std::string_view key, const nlohmann::json& value,
                                              std::size_t max_entries) const {
    if (!value.is_array()) fail(key, "expected an array of numbers, found " + typeName(value));
    if (value.size() > max_entries)
        fail(key, "array has " + std::to_string(value.size()) + " entries; at most " +
                      std::to_string(max_entries) + " are allowed");
    std::vector<double> out;
    out.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i)
        out.push_back(number(std::string(key) + "[" + std::to_string(i) + "]", value[i]));
    return out;
}

std::vector<double> ObjectReader::fixedNumberArray(std::string_view key, const nlohmann::json& value,
                                                   std::size_t count) const {
    std::vector<double> out = numberArray(key, value, count);
    if (out.size() != count)
        fail(key, "expected " + std::to_string(count) + " numbers, found " + std::to_string(out.size()));
    return out;
}

void ObjectReader::finish() const {
    for (const auto& item : m_object.items()) {
        if (std::find(m_known.begin(), m_known.end(), item.key()) != m_known.end()) continue;
        std::string allowed;
        for (const auto& k : m_known) {
            if (!allowed.empty()) allowed += ", ";
            allowed += k;
        }
        fail(item.key(), "unknown field '" + item.key() + "' (expected one of: " + allowed + ")");
    }
}

std::string ObjectReader::fieldPath(std::string_view key) const { return paintlab::fieldPath(m_path, key); }

std::string ObjectReader::elementPath(std::string_view key, std::size_t index) const {
    return paintlab::elementPath(m_path, key, index);
}

}  // namespace paintlab::jsonio
