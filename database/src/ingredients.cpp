// Ingredient repository (ingredients.h; the spectrum table itself: spectrum_rows.cpp). Each kind has its own
// table beside `ingredient`; its spectra are rows of `spectrum` referenced
// from there. Every write runs in one transaction.

#include "paintlab/database/ingredients.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/recipe_validation.h"

#include "spectrum_rows.h"
#include "sqlite.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

namespace paintlab::db {

namespace {

using detail::Connection;
using detail::Statement;
using detail::Transaction;

constexpr std::string_view kKindNames[] = {"binder", "pigment", "mirror_flake", "interference_flake",
                                           "substrate"};

std::string lowerAscii(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string fieldOf(const Ingredient& ingredient, std::string_view field) {
    std::string out = "ingredient '";
    out.append(ingredient.name).append("'");
    if (!field.empty()) out.append(".").append(field);
    return out;
}

using io::formatNumber;

// The engine's checks of one material (recipe_validation.h): the declared
// ranges and a mirror flake's reflectance-or-n,k rule; the first error is thrown.
void checkMaterialFields(const std::string& file, const Ingredient& ingredient) {
    const std::vector<RecipeProblem> problems = std::visit(
        [](const auto& data) {
            using T = std::decay_t<decltype(data)>;
            if constexpr (std::is_same_v<T, Binder> || std::is_same_v<T, Substrate>)
                return checkMaterial(data);
            else
                return checkMaterial(Component(data));
        },
        ingredient.data);
    for (const auto& problem : problems)
        if (problem.severity == Severity::Error)
            throw InputError(file, fieldOf(ingredient, problem.field), problem.message);
}

void validate(const std::string& file, const Ingredient& ingredient) {
    if (ingredient.name.empty()) throw InputError(file, "ingredient.name", "the name is empty");
    checkMaterialFields(file, ingredient);
    if (ingredient.density_g_cm3 && !(*ingredient.density_g_cm3 > 0.0 && *ingredient.density_g_cm3 < 30.0))
        throw InputError(file, fieldOf(ingredient, "density_g_cm3"),
                         formatNumber(*ingredient.density_g_cm3) + " g/cm3 is outside 0 (exclusive) to 30");
    if (!(ingredient.diameter_sd_um >= 0.0 && ingredient.diameter_sd_um < 1000.0))
        throw InputError(file, fieldOf(ingredient, "diameter_sd_um"),
                         formatNumber(ingredient.diameter_sd_um) + " µm is outside 0 to 1000");
    const bool is_binder = std::holds_alternative<Binder>(ingredient.data);
    if (ingredient.solids_mass_fraction &&
        !(is_binder && *ingredient.solids_mass_fraction > 0.0 && *ingredient.solids_mass_fraction <= 1.0))
        throw InputError(file, fieldOf(ingredient, "solids_mass_fraction"),
                         is_binder ? formatNumber(*ingredient.solids_mass_fraction) +
                                         " is outside 0 (exclusive) to 1"
                                   : std::string("only a binder has a solids content"));
    if (ingredient.volatile_density_g_cm3 &&
        !(is_binder && *ingredient.volatile_density_g_cm3 > 0.0 && *ingredient.volatile_density_g_cm3 < 30.0))
        throw InputError(file, fieldOf(ingredient, "volatile_density_g_cm3"),
                         is_binder ? formatNumber(*ingredient.volatile_density_g_cm3) +
                                         " g/cm3 is outside 0 (exclusive) to 30"
                                   : std::string("only a binder has a volatile part"));
    const auto& limits = ingredient.limits;
    if (limits.max_volume_fraction &&
        !(*limits.max_volume_fraction > 0.0 && *limits.max_volume_fraction <= 1.0))
        throw InputError(file, fieldOf(ingredient, "limits.max_volume_fraction"),
                         formatNumber(*limits.max_volume_fraction) + " is outside 0 (exclusive) to 1");
    if (limits.min_thickness_um && !(*limits.min_thickness_um >= 0.0))
        throw InputError(file, fieldOf(ingredient, "limits.min_thickness_um"), "must be >= 0");
    if (limits.max_thickness_um && !(*limits.max_thickness_um > 0.0))
        throw InputError(file, fieldOf(ingredient, "limits.max_thickness_um"), "must be > 0");
    if (limits.min_thickness_um && limits.max_thickness_um &&
        *limits.min_thickness_um > *limits.max_thickness_um)
        throw InputError(file, fieldOf(ingredient, "limits"), "min_thickness_um is above max_thickness_um");
    for (const auto& tag : ingredient.tags)
        if (tag.empty()) throw InputError(file, fieldOf(ingredient, "tags"), "a tag is empty");
}

// Inserts one spectrum of the ingredient with its provenance (or the defaults).
std::int64_t storeSpectrum(const Connection& connection, const Ingredient& ingredient,
                           const ParameterDecl& decl, const Spectrum& spectrum) {
    const auto found = ingredient.spectrum_info.find(std::string(decl.key));
    SpectrumInfo info = found != ingredient.spectrum_info.end()
                            ? found->second
                            : SpectrumInfo{std::string(decl.unit), ingredient.source, {}};
    return detail::insertSpectrum(connection, decl.key, spectrum, info);
}

std::optional<std::int64_t> storeOptional(const Connection& connection, const Ingredient& ingredient,
                                          const ParameterDecl& decl,
                                          const std::optional<Spectrum>& spectrum) {
    if (!spectrum) return std::nullopt;
    return storeSpectrum(connection, ingredient, decl, *spectrum);
}

// Writes the kind table's row for ingredient id.
void insertKindRow(const Connection& c, std::int64_t id, const Ingredient& ing) {
    std::visit(
        [&](const auto& data) {
            using T = std::decay_t<decltype(data)>;
            if constexpr (std::is_same_v<T, Binder>) {
                Statement s(c, "INSERT INTO binder (ingredient_id, refractive_index_spectrum, "
                               "absorption_per_um_spectrum, solids_mass_fraction, volatile_density_g_cm3) "
                               "VALUES (?1, ?2, ?3, ?4, ?5)");
                s.bind(1, id)
                    .bind(2, storeSpectrum(c, ing, params::kBinderIndex, data.refractive_index))
                    .bind(3, storeSpectrum(c, ing, params::kBinderAbsorption, data.absorption_per_um))
                    .bind(4, ing.solids_mass_fraction)
                    .bind(5, ing.volatile_density_g_cm3)
                    .run();
            } else if constexpr (std::is_same_v<T, Pigment>) {
                Statement s(
                    c, "INSERT INTO pigment (ingredient_id, sigma_a_per_um_spectrum, "
                       "sigma_s_per_um_spectrum, hg_g, particle_diameter_um) VALUES (?1, ?2, ?3, ?4, ?5)");
                s.bind(1, id)
                    .bind(2, storeSpectrum(c, ing, params::kPigmentSigmaA, data.sigma_a_per_um))
                    .bind(3, storeSpectrum(c, ing, params::kPigmentSigmaS, data.sigma_s_per_um))
                    .bind(4, data.hg_g)
                    .bind(5, data.particle_diameter_um)
                    .run();
            } else if constexpr (std::is_same_v<T, MirrorFlake>) {
                Statement s(
                    c, "INSERT INTO mirror_flake (ingredient_id, reflectance_spectrum, metal_n_spectrum, "
                       "metal_k_spectrum, diameter_um, diameter_sd_um, thickness_um, "
                       "orientation_spread_deg) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
                s.bind(1, id)
                    .bind(2, storeOptional(c, ing, params::kMirrorReflectance, data.reflectance))
                    .bind(3, storeOptional(c, ing, params::kMetalN, data.metal_n))
                    .bind(4, storeOptional(c, ing, params::kMetalK, data.metal_k))
                    .bind(5, data.diameter_um)
                    .bind(6, ing.diameter_sd_um)
                    .bind(7, data.thickness_um)
                    .bind(8, data.orientation_spread_deg)
                    .run();
            } else if constexpr (std::is_same_v<T, InterferenceFlake>) {
                Statement s(c, "INSERT INTO interference_flake (ingredient_id, mica_index_spectrum, "
                               "tio2_index_spectrum, mica_thickness_nm, mica_thickness_spread_nm, "
                               "tio2_thickness_nm, tio2_thickness_spread_nm, diameter_um, diameter_sd_um, "
                               "orientation_spread_deg) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)");
                s.bind(1, id)
                    .bind(2, storeSpectrum(c, ing, params::kMicaIndex, data.mica_refractive_index))
                    .bind(3, storeSpectrum(c, ing, params::kTio2Index, data.tio2_refractive_index))
                    .bind(4, data.mica_thickness_nm)
                    .bind(5, data.mica_thickness_spread_nm)
                    .bind(6, data.tio2_thickness_nm)
                    .bind(7, data.tio2_thickness_spread_nm)
                    .bind(8, data.diameter_um)
                    .bind(9, ing.diameter_sd_um)
                    .bind(10, data.orientation_spread_deg)
                    .run();
            } else {
                Statement s(
                    c,
                    "INSERT INTO substrate (ingredient_id, substrate_kind, albedo_spectrum, "
                    "metal_n_spectrum, metal_k_spectrum, refractive_index) VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
                s.bind(1, id).bind(2, substrateKind(data));
                std::optional<std::int64_t> albedo, n, k;
                std::optional<double> index;
                if (const auto* lambertian = std::get_if<LambertianSubstrate>(&data))
                    albedo = storeSpectrum(c, ing, params::kSubstrateAlbedo, lambertian->albedo);
                if (const auto* metal = std::get_if<MetalSubstrate>(&data)) {
                    n = storeSpectrum(c, ing, params::kMetalN, metal->n);
                    k = storeSpectrum(c, ing, params::kMetalK, metal->k);
                }
                if (const auto* transparent = std::get_if<TransparentSubstrate>(&data))
                    index = transparent->refractive_index;
                s.bind(3, albedo).bind(4, n).bind(5, k).bind(6, index).run();
            }
        },
        ing.data);
}

// The spectrum ids an ingredient's kind row references (to delete them with it).
std::vector<std::int64_t> kindSpectrumIds(const Connection& c, std::int64_t id) {
    static constexpr const char* kQueries[] = {
        "SELECT refractive_index_spectrum, absorption_per_um_spectrum FROM binder WHERE ingredient_id = ?1",
        "SELECT sigma_a_per_um_spectrum, sigma_s_per_um_spectrum FROM pigment WHERE ingredient_id = ?1",
        ("SELECT reflectance_spectrum, metal_n_spectrum, metal_k_spectrum FROM mirror_flake "
         "WHERE ingredient_id = ?1"),
        "SELECT mica_index_spectrum, tio2_index_spectrum FROM interference_flake WHERE ingredient_id = ?1",
        "SELECT albedo_spectrum, metal_n_spectrum, metal_k_spectrum FROM substrate WHERE ingredient_id = ?1"};
    std::vector<std::int64_t> ids;
    for (const char* sql : kQueries) {
        Statement s(c, sql);
        s.bind(1, id);
        while (s.step())
            for (int column = 0; column < s.columnCount(); ++column)
                if (auto value = s.optionalInteger(column)) ids.push_back(*value);
    }
    return ids;
}

// Removes the kind row and its spectra (before an update or a delete).
void deleteKindRow(const Connection& c, std::int64_t id) {
    const auto spectra = kindSpectrumIds(c, id);
    for (const char* table : {"binder", "pigment", "mirror_flake", "interference_flake", "substrate"}) {
        // Table names come from this fixed list, never from input.
        Statement s(c, std::string("DELETE FROM ") + table + " WHERE ingredient_id = ?1");
        s.bind(1, id).run();
    }
    Statement drop(c, "DELETE FROM spectrum WHERE id = ?1");
    for (const auto spectrum_id : spectra) {
        drop.reset();
        drop.bind(1, spectrum_id).run();
    }
}

// Sorted, without case-insensitive duplicates.
std::vector<std::string> normalisedTags(const std::vector<std::string>& tags) {
    std::vector<std::string> out;
    std::set<std::string> seen;
    for (const auto& tag : tags)
        if (seen.insert(lowerAscii(tag)).second) out.push_back(tag);
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return lowerAscii(a) < lowerAscii(b); });
    return out;
}

void writeDetails(const Connection& c, std::int64_t id, const Ingredient& ing) {
    insertKindRow(c, id, ing);
    Statement limits(c,
                     "INSERT INTO technological_limit (ingredient_id, max_volume_fraction, min_thickness_um, "
                     "max_thickness_um) VALUES (?1, ?2, ?3, ?4)");
    limits.bind(1, id)
        .bind(2, ing.limits.max_volume_fraction)
        .bind(3, ing.limits.min_thickness_um)
        .bind(4, ing.limits.max_thickness_um)
        .run();
    Statement add_tag(c, "INSERT INTO tag (name) VALUES (?1) ON CONFLICT (name) DO NOTHING");
    Statement link(
        c, "INSERT INTO ingredient_tag (ingredient_id, tag_id) SELECT ?1, id FROM tag WHERE name = ?2");
    for (const auto& tag : normalisedTags(ing.tags)) {
        add_tag.reset();
        add_tag.bind(1, tag).run();
        link.reset();
        link.bind(1, id).bind(2, tag).run();
    }
}

void throwIfDuplicate(const Connection& c, const Ingredient& ing, std::int64_t except_id) {
    Statement s(c, "SELECT id FROM ingredient WHERE kind = ?1 AND name = ?2 AND id <> ?3");
    s.bind(1, ingredientKindName(ing.kind())).bind(2, ing.name).bind(3, except_id);
    if (s.step())
        throw InputError(c.file().string(), fieldOf(ing, "name"),
                         "an ingredient of kind " + std::string(ingredientKindName(ing.kind())) +
                             " with this name already exists (id " + std::to_string(s.integer(0)) + ")");
}

Spectrum spectrumOf(const Connection& c, std::int64_t id, SpectrumInfo* info_out, std::string* quantity_out) {
    auto stored = detail::selectSpectrum(c, id);
    if (info_out != nullptr) *info_out = stored.info;
    if (quantity_out != nullptr) *quantity_out = stored.quantity;
    return std::move(stored.spectrum);
}

// Reads a spectrum into the ingredient's data and its provenance into spectrum_info.
Spectrum loadSpectrum(const Connection& c, std::int64_t id, Ingredient& ing) {
    SpectrumInfo info;
    std::string quantity;
    Spectrum spectrum = spectrumOf(c, id, &info, &quantity);
    ing.spectrum_info[quantity] = std::move(info);
    return spectrum;
}

std::optional<Spectrum> loadOptional(const Connection& c, const std::optional<std::int64_t>& id,
                                     Ingredient& ing) {
    if (!id) return std::nullopt;
    return loadSpectrum(c, *id, ing);
}

[[noreturn]] void missingKindRow(const Connection& c, const Ingredient& ing) {
    throw DatabaseError(c.file(), DatabaseError::Reason::Corrupt,
                        "ingredient " + std::to_string(ing.id) + " '" + ing.name + "' has no " +
                            std::string(ingredientKindName(ing.kind())) + " row");
}

void readKindRow(const Connection& c, const std::string& kind, Ingredient& ing) {
    if (kind == "binder") {
        Statement s(c, "SELECT refractive_index_spectrum, absorption_per_um_spectrum, solids_mass_fraction, "
                       "volatile_density_g_cm3 FROM binder WHERE ingredient_id = ?1");
        s.bind(1, ing.id);
        Binder data;
        ing.data = Binder{};
        if (!s.step()) missingKindRow(c, ing);
        data.name = ing.name;
        data.refractive_index = loadSpectrum(c, s.integer(0), ing);
        data.absorption_per_um = loadSpectrum(c, s.integer(1), ing);
        ing.solids_mass_fraction = s.optionalReal(2);
        ing.volatile_density_g_cm3 = s.optionalReal(3);
        ing.data = std::move(data);
    } else if (kind == "pigment") {
        Statement s(c, "SELECT sigma_a_per_um_spectrum, sigma_s_per_um_spectrum, hg_g, particle_diameter_um "
                       "FROM pigment WHERE ingredient_id = ?1");
        s.bind(1, ing.id);
        ing.data = Pigment{};
        if (!s.step()) missingKindRow(c, ing);
        Pigment data;
        data.name = ing.name;
        data.source = ing.source;
        data.sigma_a_per_um = loadSpectrum(c, s.integer(0), ing);
        data.sigma_s_per_um = loadSpectrum(c, s.integer(1), ing);
        data.hg_g = s.real(2);
        data.particle_diameter_um = s.real(3);
        ing.data = std::move(data);
    } else if (kind == "mirror_flake") {
        Statement s(c, "SELECT reflectance_spectrum, metal_n_spectrum, metal_k_spectrum, diameter_um, "
                       "diameter_sd_um, thickness_um, orientation_spread_deg FROM mirror_flake "
                       "WHERE ingredient_id = ?1");
        s.bind(1, ing.id);
        ing.data = MirrorFlake{};
        if (!s.step()) missingKindRow(c, ing);
        MirrorFlake data;
        data.name = ing.name;
        data.source = ing.source;
        data.reflectance = loadOptional(c, s.optionalInteger(0), ing);
        data.metal_n = loadOptional(c, s.optionalInteger(1), ing);
        data.metal_k = loadOptional(c, s.optionalInteger(2), ing);
        data.diameter_um = s.real(3);
        ing.diameter_sd_um = s.real(4);
        data.thickness_um = s.real(5);
        data.orientation_spread_deg = s.real(6);
        ing.data = std::move(data);
    } else if (kind == "interference_flake") {
        Statement s(
            c, "SELECT mica_index_spectrum, tio2_index_spectrum, mica_thickness_nm, "
               "mica_thickness_spread_nm, tio2_thickness_nm, tio2_thickness_spread_nm, diameter_um, "
               "diameter_sd_um, orientation_spread_deg FROM interference_flake WHERE ingredient_id = ?1");
        s.bind(1, ing.id);
        ing.data = InterferenceFlake{};
        if (!s.step()) missingKindRow(c, ing);
        InterferenceFlake data;
        data.name = ing.name;
        data.source = ing.source;
        data.mica_refractive_index = loadSpectrum(c, s.integer(0), ing);
        data.tio2_refractive_index = loadSpectrum(c, s.integer(1), ing);
        data.mica_thickness_nm = s.real(2);
        data.mica_thickness_spread_nm = s.real(3);
        data.tio2_thickness_nm = s.real(4);
        data.tio2_thickness_spread_nm = s.real(5);
        data.diameter_um = s.real(6);
        ing.diameter_sd_um = s.real(7);
        data.orientation_spread_deg = s.real(8);
        ing.data = std::move(data);
    } else {
        Statement s(c, "SELECT substrate_kind, albedo_spectrum, metal_n_spectrum, metal_k_spectrum, "
                       "refractive_index FROM substrate WHERE ingredient_id = ?1");
        s.bind(1, ing.id);
        ing.data = Substrate{};
        if (!s.step()) missingKindRow(c, ing);
        const std::string substrate_kind = s.text(0);
        if (substrate_kind == LambertianSubstrate::kKind)
            ing.data = Substrate{LambertianSubstrate{loadSpectrum(c, s.integer(1), ing)}};
        else if (substrate_kind == MetalSubstrate::kKind)
            ing.data = Substrate{
                MetalSubstrate{loadSpectrum(c, s.integer(2), ing), loadSpectrum(c, s.integer(3), ing)}};
        else if (substrate_kind == TransparentSubstrate::kKind)
            ing.data = Substrate{TransparentSubstrate{s.real(4)}};
        else
            ing.data = Substrate{BlackSubstrate{}};
    }
}

std::optional<Ingredient> selectIngredient(const Connection& c, Statement& s) {
    if (!s.step()) return std::nullopt;
    Ingredient ing;
    ing.id = s.integer(0);
    const std::string kind = s.text(1);
    ing.name = s.text(2);
    ing.description = s.text(3);
    ing.source = s.text(4);
    ing.density_g_cm3 = s.optionalReal(5);
    ing.density_source = s.text(6);
    readKindRow(c, kind, ing);

    Statement limits(
        c, "SELECT max_volume_fraction, min_thickness_um, max_thickness_um FROM technological_limit "
           "WHERE ingredient_id = ?1");
    limits.bind(1, ing.id);
    if (limits.step()) ing.limits = {limits.optionalReal(0), limits.optionalReal(1), limits.optionalReal(2)};
    Statement tags(c, "SELECT tag.name FROM tag JOIN ingredient_tag ON tag.id = ingredient_tag.tag_id "
                      "WHERE ingredient_tag.ingredient_id = ?1 ORDER BY tag.name COLLATE NOCASE");
    tags.bind(1, ing.id);
    while (tags.step()) ing.tags.push_back(tags.text(0));
    return ing;
}

constexpr const char* kSelectIngredient =
    "SELECT id, kind, name, description, source, density_g_cm3, density_source FROM ingredient ";

// ESCAPE-safe LIKE pattern for a substring.
std::string likePattern(std::string_view text) {
    std::string out = "%";
    for (const char c : text) {
        if (c == '%' || c == '_' || c == '\\') out.push_back('\\');
        out.push_back(c);
    }
    out.push_back('%');
    return out;
}

}  // namespace

std::string_view ingredientKindName(IngredientKind kind) {
    return kKindNames[static_cast<std::size_t>(kind)];
}

std::optional<IngredientKind> parseIngredientKind(std::string_view name) {
    for (std::size_t i = 0; i < std::size(kKindNames); ++i)
        if (kKindNames[i] == name) return static_cast<IngredientKind>(i);
    return std::nullopt;
}

IngredientKind Ingredient::kind() const noexcept { return static_cast<IngredientKind>(data.index()); }

std::int64_t createIngredient(Database& db, const Ingredient& ingredient) {
    const Connection& c = db.impl().connection;
    validate(c.file().string(), ingredient);
    Transaction transaction(c, Transaction::Mode::Write);
    throwIfDuplicate(c, ingredient, 0);
    Statement s(c, "INSERT INTO ingredient (kind, name, description, source, density_g_cm3, density_source) "
                   "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
    s.bind(1, ingredientKindName(ingredient.kind()))
        .bind(2, ingredient.name)
        .bind(3, ingredient.description)
        .bind(4, ingredient.source)
        .bind(5, ingredient.density_g_cm3)
        .bind(6, ingredient.density_source)
        .run();
    const std::int64_t id = c.lastInsertId();
    writeDetails(c, id, ingredient);
    transaction.commit();
    return id;
}

Ingredient readIngredient(Database& db, std::int64_t id) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, std::string(kSelectIngredient) + "WHERE id = ?1");
    s.bind(1, id);
    auto found = selectIngredient(c, s);
    if (!found) throw InputError(c.file().string(), "ingredient " + std::to_string(id), "no such ingredient");
    transaction.commit();
    return std::move(*found);
}

std::optional<Ingredient> findIngredient(Database& db, IngredientKind kind, std::string_view name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, std::string(kSelectIngredient) + "WHERE kind = ?1 AND name = ?2");
    s.bind(1, ingredientKindName(kind)).bind(2, name);
    auto found = selectIngredient(c, s);
    transaction.commit();
    return found;
}

void updateIngredient(Database& db, const Ingredient& ingredient) {
    const Connection& c = db.impl().connection;
    validate(c.file().string(), ingredient);
    Transaction transaction(c, Transaction::Mode::Write);
    throwIfDuplicate(c, ingredient, ingredient.id);
    Statement s(
        c, "UPDATE ingredient SET kind = ?2, name = ?3, description = ?4, source = ?5, density_g_cm3 = ?6, "
           "density_source = ?7, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?1");
    s.bind(1, ingredient.id)
        .bind(2, ingredientKindName(ingredient.kind()))
        .bind(3, ingredient.name)
        .bind(4, ingredient.description)
        .bind(5, ingredient.source)
        .bind(6, ingredient.density_g_cm3)
        .bind(7, ingredient.density_source)
        .run();
    if (c.changes() == 0)
        throw InputError(c.file().string(), "ingredient " + std::to_string(ingredient.id),
                         "no such ingredient");
    deleteKindRow(c, ingredient.id);
    for (const char* sql : {"DELETE FROM technological_limit WHERE ingredient_id = ?1",
                            "DELETE FROM ingredient_tag WHERE ingredient_id = ?1"}) {
        Statement d(c, sql);
        d.bind(1, ingredient.id).run();
    }
    writeDetails(c, ingredient.id, ingredient);
    transaction.commit();
}

void deleteIngredient(Database& db, std::int64_t id) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Write);
    Statement exists(c, "SELECT name FROM ingredient WHERE id = ?1");
    exists.bind(1, id);
    if (!exists.step())
        throw InputError(c.file().string(), "ingredient " + std::to_string(id), "no such ingredient");
    const std::string name = exists.text(0);
    Statement used(c, "SELECT count(*) FROM recipe_layer WHERE binder_ingredient_id = ?1");
    used.bind(1, id);
    Statement used_by_component(c, "SELECT count(*) FROM recipe_component WHERE ingredient_id = ?1");
    used_by_component.bind(1, id);
    used.step();
    used_by_component.step();
    const std::int64_t uses = used.integer(0) + used_by_component.integer(0);
    if (uses > 0)
        throw InputError(c.file().string(), "ingredient " + std::to_string(id) + " '" + name + "'",
                         "used by " + std::to_string(uses) +
                             " layer(s) or component(s) of saved recipe versions, which are immutable; "
                             "it cannot be deleted");
    deleteKindRow(c, id);
    Statement s(c, "DELETE FROM ingredient WHERE id = ?1");
    s.bind(1, id).run();
    transaction.commit();
}

std::vector<IngredientSummary> searchIngredients(Database& db, const IngredientFilter& filter) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    // One fixed statement; absent filters are NULL parameters. Tags: the
    // ingredient must carry as many of the wanted tags as were asked for.
    const auto wanted = normalisedTags(filter.tags);
    nlohmann::json wanted_json = nlohmann::json::array();
    for (const auto& tag : wanted) wanted_json.push_back(lowerAscii(tag));
    Statement s(
        c, "SELECT i.id, i.kind, i.name, i.density_g_cm3 FROM ingredient i "
           "WHERE (?1 IS NULL OR i.name LIKE ?1 ESCAPE '\\') AND (?2 IS NULL OR i.kind = ?2) "
           "AND (SELECT count(*) FROM ingredient_tag it JOIN tag t ON t.id = it.tag_id "
           "     WHERE it.ingredient_id = i.id AND lower(t.name) IN (SELECT value FROM json_each(?3))) = ?4 "
           "ORDER BY i.kind, i.name");
    if (filter.name_contains.empty())
        s.bindNull(1);
    else
        s.bind(1, likePattern(filter.name_contains));
    if (filter.kind)
        s.bind(2, ingredientKindName(*filter.kind));
    else
        s.bindNull(2);
    s.bind(3, wanted_json.dump()).bind(4, static_cast<std::int64_t>(wanted.size()));
    std::vector<IngredientSummary> out;
    while (s.step()) {
        IngredientSummary summary;
        summary.id = s.integer(0);
        summary.kind = parseIngredientKind(s.text(1)).value_or(IngredientKind::Binder);
        summary.name = s.text(2);
        summary.density_g_cm3 = s.optionalReal(3);
        out.push_back(std::move(summary));
    }
    Statement tags(c, "SELECT t.name FROM tag t JOIN ingredient_tag it ON t.id = it.tag_id "
                      "WHERE it.ingredient_id = ?1 ORDER BY t.name COLLATE NOCASE");
    for (auto& summary : out) {
        tags.reset();
        tags.bind(1, summary.id);
        while (tags.step()) summary.tags.push_back(tags.text(0));
    }
    transaction.commit();
    return out;
}

std::vector<StoredSpectrum> ingredientSpectra(Database& db, std::int64_t ingredient_id) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    std::vector<StoredSpectrum> out;
    for (const auto id : kindSpectrumIds(c, ingredient_id)) {
        out.push_back(detail::selectSpectrum(c, id));
        out.back().ingredient_id = ingredient_id;
    }
    transaction.commit();
    return out;
}

}  // namespace paintlab::db
