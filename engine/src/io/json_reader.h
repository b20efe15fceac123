#pragma once
// Reading untrusted JSON files (recipes, scenes, ray-map heads, database
// imports): a size cap checked before anything is read, a nesting-depth cap
// enforced while parsing, parse errors turned into InputError messages with
// line, column and the field being read, and ObjectReader, which reads the
// fields of one object and reports a misspelt or unknown key instead of
// silently ignoring it. Field paths are dotted, arrays indexed from 0:
// "layers[1].components[0].volume_fraction".
// Private to PaintLab's libraries and programs (it names nlohmann types):
// reached through the PaintLab::engine_json target, see engine/CMakeLists.txt.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::jsonio {

// Reads a whole file of at most max_bytes. Throws InputError naming the file
// if it is missing, unreadable, a directory, empty, or larger than max_bytes
// (checked from the file size, so a huge file is rejected without reading it).
std::string readBoundedTextFile(const std::filesystem::path& path, std::size_t max_bytes);

// Parses text as one JSON value, nesting at most max_depth. Throws InputError
// naming source, the line and column, and the last key before the error.
nlohmann::json parseUntrustedJson(std::string_view text, const std::string& source,
                                  std::size_t max_depth = 64);

// "a number", "an object", ... for messages.
std::string typeName(const nlohmann::json& value);

// Reads the fields of one JSON object, remembering which keys were asked for
// so that finish() can report a key nobody reads (a typo) by name. Every
// failure is an InputError naming source and the path of the field
// ("layers[0].thickness_um").
class ObjectReader {
public:
    ObjectReader(const nlohmann::json& object, std::string path, const std::string& source);

    [[noreturn]] void fail(std::string_view key, const std::string& message) const;
    // nullptr when absent.
    const nlohmann::json* find(std::string_view key);
    const nlohmann::json& require(std::string_view key, std::string_view what);
    // Whether the object has key (without taking it).
    bool has(std::string_view key) const { return m_object.contains(key); }

    std::string string(std::string_view key, bool required);
    // A finite number; value is the JSON found at key.
    double number(std::string_view key, const nlohmann::json& value) const;
    double number(std::string_view key, std::string_view what) { return number(key, require(key, what)); }
    // A finite number, or nullopt when the key is absent.
    std::optional<double> optionalNumber(std::string_view key);
    // A number in [lo, hi] ((lo, hi] with lo_exclusive); required unless a
    // fallback is given for an absent key.
    double numberIn(std::string_view key, double lo, double hi, std::optional<double> fallback = std::nullopt,
                    bool lo_exclusive = false);
    // A whole number in [lo, hi]; required unless a fallback is given.
    int integerIn(std::string_view key, int lo, int hi, std::optional<int> fallback = std::nullopt);
    // At most max_entries finite numbers.
    std::vector<double> numberArray(std::string_view key, const nlohmann::json& value,
                                    std::size_t max_entries = kMaxArrayEntries) const;
    // The required array at key, of at least min_entries finite numbers.
    std::vector<double> numbers(std::string_view key, std::size_t min_entries = 0);
    // Exactly `count` finite numbers (a 3-vector, say).
    std::vector<double> fixedNumberArray(std::string_view key, const nlohmann::json& value,
                                         std::size_t count) const;

    // Every key of the object must have been asked for.
    void finish() const;
    // "path.key"; elementPath gives "path.key[index]" for an array's entry.
    std::string fieldPath(std::string_view key) const;
    std::string elementPath(std::string_view key, std::size_t index) const;
    const std::string& source() const { return m_source; }

    // Arrays longer than this are not data but garbage (a tabulated spectrum
    // has hundreds of samples).
    static constexpr std::size_t kMaxArrayEntries = 100000;

private:
    const nlohmann::json& m_object;
    std::string m_path;
    const std::string& m_source;
    std::vector<std::string> m_known;
};

}  // namespace paintlab::jsonio
