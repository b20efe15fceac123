#include "ingredient_fields.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

namespace paintlab::gui {

namespace {

using Type = IngredientField::Type;

// Calls fn(decl, value) for every scalar of the optical data but the
// recipe's own volume fraction (kept 0 in the database).
template <class Fn> struct ScalarVisitor {
    Fn fn;
    template <class D> void scalar(const ParameterDecl& decl, D& value) {
        if (decl.key != "volume_fraction") fn(decl, value);
    }
    template <class S> void spectrum(const ParameterDecl& /*decl*/, S& /*value*/) {}
    template <class S> void optionalSpectrum(const ParameterDecl& /*decl*/, S& /*value*/) {}
};

template <class Data, class Fn> void visitScalars(Data& data, Fn fn) {
    ScalarVisitor<Fn> v{std::move(fn)};
    std::visit(
        [&](auto& d) {
            using T = std::remove_cvref_t<decltype(d)>;
            if constexpr (std::is_same_v<T, Substrate>) {
                std::visit([&](auto& s) { std::remove_cvref_t<decltype(s)>::traverse(s, v); }, d);
            } else {
                T::traverse(d, v);
            }
        },
        data);
}

std::string displayUnit(std::string_view unit) { return unit == "1" ? std::string() : std::string(unit); }

std::string formatNumber(double value) { return io::formatNumber(value, io::NumberFormat::Shortest); }

std::string_view trim(std::string_view text) {
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!text.empty() && space(text.front())) text.remove_prefix(1);
    while (!text.empty() && space(text.back())) text.remove_suffix(1);
    return text;
}

std::string fieldPath(const db::Ingredient& ingredient, const std::string& key) {
    return "ingredient '" + ingredient.name + "'." + key;
}

// An empty text gives nullopt; anything else must be one finite number.
std::optional<double> parseNumber(const db::Ingredient& ingredient, const IngredientField& field,
                                  std::string_view text, const std::string& source) {
    const std::string_view t = trim(text);
    if (t.empty()) {
        if (field.type == Type::Number)
            throw InputError(source, fieldPath(ingredient, field.key), "a number is required");
        return std::nullopt;
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(value))
        throw InputError(source, fieldPath(ingredient, field.key),
                         "'" + std::string(t) + "' is not a number");
    return value;
}

// Field lookups for a const or a mutable ingredient.
template <class I> auto* scalarOf(I& ingredient, std::string_view key) {
    decltype(&ingredient.diameter_sd_um) found = nullptr;
    visitScalars(ingredient.data, [&](const ParameterDecl& decl, auto& value) {
        if (decl.key == key) found = &value;
    });
    return found;
}

template <class I> auto* optionalOf(I& ingredient, std::string_view key) {
    using Result = decltype(&ingredient.density_g_cm3);
    if (key == "density_g_cm3") return &ingredient.density_g_cm3;
    if (key == "solids_mass_fraction") return &ingredient.solids_mass_fraction;
    if (key == "volatile_density_g_cm3") return &ingredient.volatile_density_g_cm3;
    if (key == "limits.max_volume_fraction") return &ingredient.limits.max_volume_fraction;
    if (key == "limits.min_thickness_um") return &ingredient.limits.min_thickness_um;
    if (key == "limits.max_thickness_um") return &ingredient.limits.max_thickness_um;
    return Result{nullptr};
}

template <class I> auto* textOf(I& ingredient, std::string_view key) {
    using Result = decltype(&ingredient.name);
    if (key == "name") return &ingredient.name;
    if (key == "description") return &ingredient.description;
    if (key == "source") return &ingredient.source;
    if (key == "density_source") return &ingredient.density_source;
    return Result{nullptr};
}

}  // namespace

std::string ingredientKindLabel(db::IngredientKind kind) {
    std::string name(db::ingredientKindName(kind));
    for (char& c : name)
        if (c == '_') c = ' ';
    return name;
}

std::vector<IngredientField> ingredientFields(const db::Ingredient& ingredient) {
    const db::IngredientKind kind = ingredient.kind();
    std::vector<IngredientField> out = {
        {"name", "Name", "", Type::Text, "Unique within its kind; recipes link to it by kind and name"},
        {"description", "Description", "", Type::LongText, ""},
        {"source", "Source", "", Type::Text, "Literature reference, supplier data sheet or measurement"},
        {"tags", "Tags", "", Type::Tags, "Comma-separated"},
        {"density_g_cm3", kind == db::IngredientKind::Binder ? "Density (dry film)" : "Density", "g/cm³",
         Type::OptionalNumber, "Needed for production sheets"},
        {"density_source", "Density source", "", Type::Text, ""},
    };
    visitScalars(ingredient.data, [&](const ParameterDecl& decl, const double& /*value*/) {
        out.push_back({std::string(decl.key), std::string(decl.label), displayUnit(decl.unit), Type::Number,
                       std::string(decl.help)});
    });
    if (kind == db::IngredientKind::MirrorFlake || kind == db::IngredientKind::InterferenceFlake)
        out.push_back({"diameter_sd_um", "Diameter standard deviation", "µm", Type::Number,
                       "Spread of the flake diameter distribution"});
    if (kind == db::IngredientKind::Binder) {
        out.push_back({"solids_mass_fraction", "Solids mass fraction", "", Type::OptionalNumber,
                       "Non-volatile content as bought (empty: 100 % solids)"});
        out.push_back({"volatile_density_g_cm3", "Density of the volatiles", "g/cm³", Type::OptionalNumber,
                       "Solvent or water"});
    }
    if (kind != db::IngredientKind::Substrate) {
        out.push_back({"limits.max_volume_fraction", "Max. volume fraction", "", Type::OptionalNumber,
                       "Technological limit: what can be dispersed and still form a film"});
        out.push_back({"limits.min_thickness_um", "Min. dry film thickness", "µm", Type::OptionalNumber,
                       "Technological limit"});
        out.push_back({"limits.max_thickness_um", "Max. dry film thickness", "µm", Type::OptionalNumber,
                       "Technological limit"});
    }
    return out;
}

std::string fieldText(const db::Ingredient& ingredient, const IngredientField& field) {
    if (field.type == Type::Tags) {
        std::string out;
        for (const std::string& tag : ingredient.tags) out += (out.empty() ? "" : ", ") + tag;
        return out;
    }
    if (const std::string* text = textOf(ingredient, field.key)) return *text;
    if (const std::optional<double>* value = optionalOf(ingredient, field.key))
        return *value ? formatNumber(**value) : std::string();
    if (field.key == "diameter_sd_um") return formatNumber(ingredient.diameter_sd_um);
    if (const double* value = scalarOf(ingredient, field.key)) return formatNumber(*value);
    return {};
}

void setFieldText(db::Ingredient& ingredient, const IngredientField& field, std::string_view text,
                  const std::string& source) {
    if (field.type == Type::Tags) {
        std::vector<std::string> tags;
        std::string_view rest = text;
        while (!rest.empty()) {
            const std::size_t comma = rest.find(',');
            const std::string_view tag = trim(rest.substr(0, comma));
            if (!tag.empty()) tags.emplace_back(tag);
            rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
        }
        ingredient.tags = std::move(tags);
        return;
    }
    if (std::string* target = textOf(ingredient, field.key)) {
        *target = field.type == Type::LongText ? std::string(text) : std::string(trim(text));
        return;
    }
    const std::optional<double> value = parseNumber(ingredient, field, text, source);
    if (std::optional<double>* target = optionalOf(ingredient, field.key)) {
        *target = value;
    } else if (field.key == "diameter_sd_um") {
        ingredient.diameter_sd_um = *value;
    } else if (double* scalar = scalarOf(ingredient, field.key)) {
        *scalar = *value;
    } else {
        throw InputError(source, fieldPath(ingredient, field.key), "no such field");
    }
}

std::string fieldKeyOfError(const std::vector<IngredientField>& fields, std::string_view error_field) {
    std::string best;
    for (const IngredientField& field : fields) {
        const std::string suffix = "." + field.key;
        const bool ends = error_field.size() >= suffix.size() &&
                          error_field.substr(error_field.size() - suffix.size()) == suffix;
        // "ingredient.name" (the database's empty-name error) names the name field too.
        if ((ends || error_field == field.key) && field.key.size() > best.size()) best = field.key;
    }
    // A spectrum sample ("...refractive_index[3]") or the limits as a whole: the nearest field.
    if (best.empty() && error_field.ends_with(".limits")) best = "limits.min_thickness_um";
    return best;
}

}  // namespace paintlab::gui
