#pragma once
// Strict reading of one JSON object in the database's import files
// (ingredients, measurements): every key is either taken or reported as
// unknown, so a misspelt field never passes silently, and every failure is an
// InputError naming the file and the dotted path of the field
// ("ingredients[2].limits.max_volume_fraction").

#include "paintlab/engine/error.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace paintlab::db::detail {

class JsonFields {
public:
    using Json = nlohmann::json;

    JsonFields(const Json& object, std::string field, const std::string& source)
        : m_object(object), m_field(std::move(field)), m_source(source) {
        if (!object.is_object()) fail("", "expected an object");
    }

    bool has(const std::string& key) const { return m_object.contains(key); }

    const Json& get(const std::string& key) {
        if (!m_object.contains(key)) fail(key, "missing");
        m_taken.insert(key);
        return m_object.at(key);
    }

    std::string text(const std::string& key) {
        const Json& value = get(key);
        if (!value.is_string()) fail(key, "expected a string");
        return value.get<std::string>();
    }
    std::string optionalText(const std::string& key) { return has(key) ? text(key) : std::string(); }

    double number(const std::string& key) {
        const Json& value = get(key);
        if (!value.is_number()) fail(key, "expected a number");
        return value.get<double>();
    }
    std::optional<double> optionalNumber(const std::string& key) {
        if (!has(key)) return std::nullopt;
        return number(key);
    }

    // An array of at least min_size numbers; a bad entry is named by index.
    std::vector<double> numbers(const std::string& key, std::size_t min_size = 0) {
        const Json& value = get(key);
        if (!value.is_array() || value.size() < min_size)
            fail(key,
                 min_size > 0 ? "expected a non-empty array of numbers" : "expected an array of numbers");
        std::vector<double> out;
        out.reserve(value.size());
        for (std::size_t i = 0; i < value.size(); ++i) {
            if (!value[i].is_number()) fail(key + "[" + std::to_string(i) + "]", "expected a number");
            out.push_back(value[i].get<double>());
        }
        return out;
    }

    std::string fieldOf(const std::string& key) const { return key.empty() ? m_field : m_field + "." + key; }

    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        throw InputError(m_source, fieldOf(key), message);
    }

    void finish() const {
        for (const auto& item : m_object.items())
            if (m_taken.count(item.key()) == 0) fail(item.key(), "unknown field");
    }

private:
    const Json& m_object;
    std::string m_field;
    const std::string& m_source;
    std::set<std::string> m_taken;
};

}  // namespace paintlab::db::detail
