#include "recipe_diff.h"

#include "paintlab/engine/recipe_json.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace paintlab::gui {

namespace {

// Ordered: the changes come in the document's order.
using json = nlohmann::ordered_json;

bool isSpectrum(const json& j) {
    return j.is_object() && j.contains("wavelengths_nm") && j.contains("values");
}

// The shortest text that reads back exactly, without a trailing ".0".
std::string number(double v) {
    if (std::abs(v) < 1e15 && v == std::floor(v)) return std::to_string(static_cast<long long>(v));
    return json(v).dump();
}

// A short text for a value of any kind.
std::string summary(const json& j) {
    if (isSpectrum(j)) {
        const json& w = j["wavelengths_nm"];
        const json& v = j["values"];
        if (w.empty() || v.empty()) return "spectrum";
        double lo = v.front().get<double>();
        double hi = lo;
        for (const json& x : v) {
            lo = std::min(lo, x.get<double>());
            hi = std::max(hi, x.get<double>());
        }
        return "spectrum, " + std::to_string(v.size()) + " samples " + number(w.front().get<double>()) + "-" +
               number(w.back().get<double>()) + " nm, values " + number(lo) + " to " + number(hi);
    }
    if (j.is_object()) {
        std::string out = j.contains("kind") && j["kind"].is_string() ? j["kind"].get<std::string>() : "";
        if (j.contains("name") && j["name"].is_string())
            out += (out.empty() ? "'" : " '") + j["name"].get<std::string>() + "'";
        return out.empty() ? "{...}" : out;
    }
    if (j.is_array()) {
        std::string out = "[";
        for (std::size_t i = 0; i < j.size() && i < 8; ++i) out += (i ? ", " : "") + summary(j[i]);
        return out + (j.size() > 8 ? ", ...]" : "]");
    }
    if (j.is_string()) {
        std::string s = j.get<std::string>();
        if (s.size() > 80) s = s.substr(0, 77) + "...";
        return "\"" + s + "\"";
    }
    if (j.is_number_float()) return number(j.get<double>());
    return j.dump();
}

// The identity of an array element for matching: kind and name.
std::string identity(const json& j) {
    if (!j.is_object() || !j.contains("name") || !j["name"].is_string()) return {};
    const std::string kind = j.contains("kind") && j["kind"].is_string() ? j["kind"].get<std::string>() : "";
    return kind + "\x1f" + j["name"].get<std::string>();
}

std::string elementPath(const std::string& path, std::size_t index, const json& element) {
    std::string out = path + "[" + std::to_string(index) + "]";
    if (element.is_object() && element.contains("name") && element["name"].is_string())
        out += " '" + element["name"].get<std::string>() + "'";
    return out;
}

class Differ {
public:
    std::vector<RecipeChange> changes;

    void walk(const json& a, const json& b, const std::string& path) {
        if (a == b) return;
        if (isSpectrum(a) && isSpectrum(b)) {
            spectrum(a, b, path);
        } else if (a.is_object() && b.is_object() && !isSpectrum(a) && !isSpectrum(b)) {
            object(a, b, path);
        } else if (a.is_array() && b.is_array() && matchable(a, b)) {
            array(a, b, path);
        } else {
            changes.push_back({path, summary(a), summary(b)});
        }
    }

private:
    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }

    void object(const json& a, const json& b, const std::string& path) {
        for (const auto& [key, value] : a.items()) {
            if (b.contains(key)) {
                walk(value, b[key], join(path, key));
            } else {
                changes.push_back({join(path, key), summary(value), kAbsent});
            }
        }
        for (const auto& [key, value] : b.items())
            if (!a.contains(key)) changes.push_back({join(path, key), kAbsent, summary(value)});
    }

    // Arrays of named objects whose names are unique in each: matched by name.
    static bool matchable(const json& a, const json& b) {
        for (const json* arr : {&a, &b}) {
            std::set<std::string> seen;
            for (const json& e : *arr) {
                const std::string id = identity(e);
                if (id.empty() || !seen.insert(id).second) return false;
            }
        }
        return true;
    }

    void array(const json& a, const json& b, const std::string& path) {
        std::vector<std::string> common_a;
        std::vector<std::string> common_b;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const std::string id = identity(a[i]);
            const auto in_b =
                std::find_if(b.begin(), b.end(), [&](const json& e) { return identity(e) == id; });
            if (in_b == b.end()) {
                changes.push_back({elementPath(path, i, a[i]), summary(a[i]), kAbsent});
                continue;
            }
            common_a.push_back(id);
            walk(a[i], *in_b, elementPath(path, static_cast<std::size_t>(in_b - b.begin()), *in_b));
        }
        for (std::size_t i = 0; i < b.size(); ++i) {
            const std::string id = identity(b[i]);
            const bool in_a =
                std::any_of(a.begin(), a.end(), [&](const json& e) { return identity(e) == id; });
            if (!in_a) {
                changes.push_back({elementPath(path, i, b[i]), kAbsent, summary(b[i])});
            } else {
                common_b.push_back(id);
            }
        }
        if (common_a != common_b) {
            const auto names = [](const std::vector<std::string>& ids) {
                std::string out;
                for (const std::string& id : ids)
                    out += (out.empty() ? "" : ", ") + id.substr(id.find('\x1f') + 1);
                return out;
            };
            changes.push_back({path + " (order)", names(common_a), names(common_b)});
        }
    }

    void spectrum(const json& a, const json& b, const std::string& path) {
        std::string after = summary(b);
        if (a["wavelengths_nm"] == b["wavelengths_nm"] && a["values"].size() == b["values"].size()) {
            double largest = 0.0;
            std::size_t at = 0;
            for (std::size_t i = 0; i < a["values"].size(); ++i) {
                const double d = std::abs(b["values"][i].get<double>() - a["values"][i].get<double>());
                if (d > largest) {
                    largest = d;
                    at = i;
                }
            }
            after += " (largest change " + number(largest) + " at " +
                     number(b["wavelengths_nm"][at].get<double>()) + " nm)";
        }
        changes.push_back({path, summary(a), after});
    }
};

}  // namespace

std::vector<RecipeChange> diffRecipes(const Recipe& before, const Recipe& after) {
    if (before == after) return {};
    Differ differ;
    differ.walk(json::parse(recipeToJson(before)), json::parse(recipeToJson(after)), "");
    return std::move(differ.changes);
}

}  // namespace paintlab::gui
