#pragma once
// Ingredients: what recipes are made of, stored with the provenance of their
// data. The optical data are the engine's own types (recipe.h), so an
// ingredient drops into a Recipe as it is (set its volume fraction); the
// database adds what a recipe does not carry: density, tags, technological
// limits, the spread of the flake diameter, and for every spectrum its unit,
// source and date.

#include "paintlab/database/database.h"
#include "paintlab/engine/recipe.h"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace paintlab::db {

enum class IngredientKind { Binder, Pigment, MirrorFlake, InterferenceFlake, Substrate };

// "binder", "pigment", "mirror_flake", "interference_flake", "substrate"
// (the engine's component kinds where there is one).
std::string_view ingredientKindName(IngredientKind kind);
std::optional<IngredientKind> parseIngredientKind(std::string_view name);

// The optical data, one engine type per kind. The volume fraction and depth
// profile of a component belong to a recipe and are not stored (kept 0 / empty).
using IngredientData = std::variant<Binder, Pigment, MirrorFlake, InterferenceFlake, Substrate>;

// Provenance of one spectrum of an ingredient.
struct SpectrumInfo {
    std::string unit;    // "1" (dimensionless), "1/µm"
    std::string source;  // literature reference, instrument or method
    std::string date;    // when measured or published (ISO 8601 date or year); may be empty
    friend bool operator==(const SpectrumInfo&, const SpectrumInfo&) = default;
};

struct TechnologicalLimits {
    std::optional<double> max_volume_fraction;  // what can be dispersed and still form a film
    std::optional<double> min_thickness_um;     // dry film thickness range
    std::optional<double> max_thickness_um;
    friend bool operator==(const TechnologicalLimits&, const TechnologicalLimits&) = default;
};

struct Ingredient {
    std::int64_t id = 0;  // 0 until stored
    std::string name;     // unique within its kind; recipes link to ingredients by kind and name
    std::string description;
    std::string source;  // where the ingredient's data come from, as a whole
    std::optional<double> density_g_cm3;
    std::string density_source;
    std::vector<std::string> tags;  // stored sorted, without duplicates (case-insensitive)
    TechnologicalLimits limits;
    // Flakes: standard deviation of the diameter distribution. Adding the
    // ingredient to a recipe copies it into the component (MirrorFlake /
    // InterferenceFlake::diameter_sd_um; gui/src/recipe_ingredient.cpp).
    double diameter_sd_um = 0.0;
    // Binders as bought (schema 2), for production sheets: the non-volatile
    // (solids) mass fraction of the resin solution or dispersion (unset: weighed
    // as 100 % solids) and the density of its volatile part (solvent, water),
    // g/cm3. density_g_cm3 of a binder is the density of its dry film.
    std::optional<double> solids_mass_fraction;
    std::optional<double> volatile_density_g_cm3;
    // The name and source fields of the engine struct are not stored: they
    // are the ingredient's own (readIngredient sets them).
    IngredientData data;
    // Provenance per spectrum, keyed by the recipe field's key ("refractive_index",
    // "metal_n", "sigma_a_per_um", ...). A spectrum without an entry is stored
    // with the unit of its declaration (parameters.h) and the ingredient's source.
    std::map<std::string, SpectrumInfo> spectrum_info;

    IngredientKind kind() const noexcept;
    friend bool operator==(const Ingredient&, const Ingredient&) = default;
};

struct IngredientSummary {
    std::int64_t id = 0;
    IngredientKind kind = IngredientKind::Binder;
    std::string name;
    std::vector<std::string> tags;
    std::optional<double> density_g_cm3;
};

struct IngredientFilter {
    std::string name_contains;  // case-insensitive substring; empty = any
    std::optional<IngredientKind> kind;
    std::vector<std::string> tags;  // the ingredient has every one of them (case-insensitive)
};

// Each function throws DatabaseError naming the file when SQLite fails
// (locked, read-only, full, corrupt), and InputError(file, field, message)
// when the ingredient itself is wrong (empty name, value out of range, a
// duplicate kind + name, an unknown id); nothing is written then.

// Stores a new ingredient (the id field is ignored); returns its id.
std::int64_t createIngredient(Database& db, const Ingredient& ingredient);
Ingredient readIngredient(Database& db, std::int64_t id);
std::optional<Ingredient> findIngredient(Database& db, IngredientKind kind, std::string_view name);
// Replaces every field of the stored ingredient ingredient.id (its kind included).
void updateIngredient(Database& db, const Ingredient& ingredient);
// Refused (InputError) while a saved recipe version uses the ingredient:
// versions are immutable and keep their links.
void deleteIngredient(Database& db, std::int64_t id);
// Sorted by kind, then name.
std::vector<IngredientSummary> searchIngredients(Database& db, const IngredientFilter& filter = {});

// A stored spectrum on its own (ingredient spectra included), for listing and plotting.
struct StoredSpectrum {
    std::int64_t id = 0;
    std::string name;      // spectra stored on their own have a unique name; ingredient spectra none
    std::string quantity;  // "refractive_index", "metal_k", "albedo", ...
    SpectrumInfo info;
    Spectrum spectrum;
    std::optional<std::int64_t> ingredient_id;  // the ingredient it belongs to, if any
};

// Stores a spectrum that belongs to no ingredient (a measured one); returns its id.
std::int64_t addSpectrum(Database& db, std::string_view quantity, const Spectrum& spectrum,
                         const SpectrumInfo& info);
// The same with a name, unique among named spectra (InputError naming the
// file and the name if it is taken or empty).
std::int64_t addNamedSpectrum(Database& db, std::string_view name, std::string_view quantity,
                              const Spectrum& spectrum, const SpectrumInfo& info);
std::optional<StoredSpectrum> findNamedSpectrum(Database& db, std::string_view name);
// Every named spectrum, by name.
std::vector<StoredSpectrum> namedSpectra(Database& db);
StoredSpectrum readSpectrum(Database& db, std::int64_t id);
// The spectra of one ingredient, in a stable order.
std::vector<StoredSpectrum> ingredientSpectra(Database& db, std::int64_t ingredient_id);

}  // namespace paintlab::db
