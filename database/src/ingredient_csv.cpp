// Ingredient CSV files (ingredient_csv.h): each ingredient's records are
// gathered into the JSON object of the ingredient file format and read by
// its strict reader, so both formats accept exactly the same ingredients.

#include "paintlab/database/ingredient_csv.h"

#include "ingredient_json_detail.h"
#include "spectrum_checks.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <iterator>
#include <map>

namespace paintlab::db {

namespace {

using io::CsvRecord;
using io::CsvTable;
using Json = nlohmann::json;

// The ingredient's own fields, in file order: text columns, then numbers.
constexpr std::string_view kTextColumns[] = {"kind", "name",           "description",   "source",
                                             "tags", "density_source", "substrate_kind"};
constexpr std::string_view kNumberColumns[] = {"density_g_cm3",
                                               "max_volume_fraction",
                                               "min_thickness_um",
                                               "max_thickness_um",
                                               "solids_mass_fraction",
                                               "volatile_density_g_cm3",
                                               "hg_g",
                                               "particle_diameter_um",
                                               "diameter_um",
                                               "diameter_sd_um",
                                               "thickness_um",
                                               "orientation_spread_deg",
                                               "mica_thickness_nm",
                                               "mica_thickness_spread_nm",
                                               "tio2_thickness_nm",
                                               "tio2_thickness_spread_nm",
                                               "refractive_index"};
constexpr std::string_view kLimitColumns[] = {"max_volume_fraction", "min_thickness_um", "max_thickness_um"};
constexpr std::string_view kSpectrumColumns[] = {"spectrum",      "unit",          "spectrum_source",
                                                 "spectrum_date", "wavelength_nm", "value"};

// The header as written: kind, name, description, source, tags, density,
// density source, then the other numbers and the spectrum columns.
std::vector<std::string_view> allColumns() {
    std::vector<std::string_view> out = {"kind", "name",          "description",   "source",
                                         "tags", "density_g_cm3", "density_source"};
    for (const auto c : kNumberColumns)
        if (c != "density_g_cm3") out.push_back(c);
    out.insert(out.begin() + 12, "substrate_kind");  // after volatile_density_g_cm3
    for (const auto c : kSpectrumColumns) out.push_back(c);
    return out;
}

bool isLimit(std::string_view column) {
    for (const auto c : kLimitColumns)
        if (c == column) return true;
    return false;
}

using io::formatNumber;

struct SpectrumRecords {
    std::string key;
    std::vector<const CsvRecord*> records;
};

struct IngredientRecords {
    std::string kind;
    std::string name;
    std::vector<const CsvRecord*> records;
    std::vector<SpectrumRecords> spectra;
};

// The same field on every record of the ingredient (or the spectrum).
void requireAgreement(const CsvTable& table, const std::vector<const CsvRecord*>& records,
                      std::string_view column, std::string_view what) {
    const std::string& first = table.field(*records.front(), column);
    for (const auto* record : records)
        if (table.field(*record, column) != first)
            throw InputError(table.source(), CsvTable::where(*record, column),
                             "'" + table.field(*record, column) + "' differs from '" + first + "' on line " +
                                 std::to_string(records.front()->line) + " of the same " + std::string(what));
}

Json spectrumJson(const CsvTable& table, const SpectrumRecords& spectrum) {
    for (const auto column : {"unit", "spectrum_source", "spectrum_date"})
        requireAgreement(table, spectrum.records, column, "spectrum");
    const CsvRecord& first = *spectrum.records.front();
    Json out{{"unit", table.field(first, "unit")}, {"source", table.field(first, "spectrum_source")}};
    if (!table.field(first, "spectrum_date").empty()) out["date"] = table.field(first, "spectrum_date");
    if (table.field(first, "unit").empty())
        throw InputError(table.source(), CsvTable::where(first, "unit"),
                         "empty; every spectrum needs a unit");
    const bool constant = table.field(first, "wavelength_nm").empty();
    if (constant) {
        if (spectrum.records.size() > 1)
            throw InputError(table.source(), CsvTable::where(*spectrum.records[1], "wavelength_nm"),
                             "spectrum '" + spectrum.key +
                                 "' has a constant value (empty wavelength_nm on line " +
                                 std::to_string(first.line) + ") and more samples");
        out["value"] = table.requiredNumber(first, "value");
        return out;
    }
    Json wavelengths = Json::array();
    Json values = Json::array();
    double previous = 0.0;
    for (std::size_t i = 0; i < spectrum.records.size(); ++i) {
        const CsvRecord& record = *spectrum.records[i];
        const double wavelength = table.requiredNumber(record, "wavelength_nm");
        if (wavelength <= 0.0)
            throw InputError(table.source(), CsvTable::where(record, "wavelength_nm"),
                             formatNumber(wavelength) + " nm: a wavelength must be positive");
        if (i > 0 && wavelength <= previous)
            throw InputError(table.source(), CsvTable::where(record, "wavelength_nm"),
                             formatNumber(wavelength) + " nm does not increase on " + formatNumber(previous) +
                                 " nm (line " + std::to_string(spectrum.records[i - 1]->line) +
                                 "): the samples of a spectrum are in strictly increasing wavelength");
        previous = wavelength;
        wavelengths.push_back(wavelength);
        values.push_back(table.requiredNumber(record, "value"));
    }
    out["wavelengths_nm"] = std::move(wavelengths);
    out["values"] = std::move(values);
    return out;
}

Json ingredientJson(const CsvTable& table, const IngredientRecords& ingredient) {
    for (const auto column : kTextColumns) requireAgreement(table, ingredient.records, column, "ingredient");
    for (const auto column : kNumberColumns)
        requireAgreement(table, ingredient.records, column, "ingredient");
    const CsvRecord& first = *ingredient.records.front();
    Json out = Json::object();
    for (const auto column : kTextColumns) {
        const std::string& text = table.field(first, column);
        if (column == "tags") {
            Json tags = Json::array();
            std::size_t start = 0;
            while (!text.empty() && start <= text.size()) {
                const auto bar = text.find('|', start);
                tags.push_back(
                    text.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
                if (bar == std::string::npos) break;
                start = bar + 1;
            }
            if (!tags.empty()) out["tags"] = tags;
        } else if (!text.empty() || (column != "substrate_kind" && table.column(column))) {
            out[std::string(column)] = text;
        }
    }
    Json limits = Json::object();
    for (const auto column : kNumberColumns) {
        const auto value = table.number(first, column);
        if (!value) continue;
        if (isLimit(column))
            limits[std::string(column)] = *value;
        else
            out[std::string(column)] = *value;
    }
    if (!limits.empty()) out["limits"] = limits;
    Json spectra = Json::object();
    for (const auto& spectrum : ingredient.spectra) spectra[spectrum.key] = spectrumJson(table, spectrum);
    out["spectra"] = spectra;
    return out;
}

}  // namespace

std::vector<Ingredient> parseIngredientsCsv(std::string_view text, const std::string& source) {
    const CsvTable table = CsvTable::parse(text, source);
    table.requireColumns({"kind", "name", "spectrum", "wavelength_nm", "value"});
    table.allowOnlyColumns(allColumns());

    // Gather the records by ingredient (kind, name) and spectrum, in file order.
    std::vector<IngredientRecords> ingredients;
    std::map<std::pair<std::string, std::string>, std::size_t> index;
    for (const auto& record : table.records()) {
        const std::string& kind = table.field(record, "kind");
        const std::string& name = table.field(record, "name");
        if (kind.empty())
            throw InputError(source, CsvTable::where(record, "kind"), "empty; every record needs a kind");
        if (name.empty())
            throw InputError(source, CsvTable::where(record, "name"), "empty; every record needs a name");
        auto [it, added] = index.try_emplace({kind, name}, ingredients.size());
        if (added) ingredients.push_back({kind, name, {}, {}});
        IngredientRecords& ingredient = ingredients[it->second];
        ingredient.records.push_back(&record);
        const std::string& key = table.field(record, "spectrum");
        if (key.empty()) {
            for (const auto column : {"unit", "spectrum_source", "spectrum_date", "wavelength_nm", "value"})
                if (!table.field(record, column).empty())
                    throw InputError(source, CsvTable::where(record, column),
                                     "a value without a spectrum: the spectrum column is empty");
            continue;
        }
        auto spectrum = std::find_if(ingredient.spectra.begin(), ingredient.spectra.end(),
                                     [&](const auto& s) { return s.key == key; });
        if (spectrum == ingredient.spectra.end()) {
            ingredient.spectra.push_back({key, {}});
            spectrum = std::prev(ingredient.spectra.end());
        }
        spectrum->records.push_back(&record);
    }

    std::vector<Ingredient> out;
    for (const auto& ingredient : ingredients) {
        const std::string field = "line " + std::to_string(ingredient.records.front()->line) + " (" +
                                  ingredient.kind + " '" + ingredient.name + "')";
        Ingredient ing = detail::ingredientFromJson(ingredientJson(table, ingredient), field, source);
        detail::normaliseIngredientSpectra(ing, source, field);
        out.push_back(std::move(ing));
    }
    return out;
}

std::string ingredientsToCsv(const std::vector<Ingredient>& ingredients) {
    const auto columns = allColumns();
    std::vector<std::string> header(columns.begin(), columns.end());
    std::string out = io::csvLine(header);
    for (const auto& ingredient : ingredients) {
        const nlohmann::ordered_json json = detail::ingredientToJson(ingredient);
        // The ingredient's own fields, the same on each of its records.
        std::map<std::string_view, std::string> own;
        for (const auto column : kTextColumns) {
            if (column == "tags") {
                std::string tags;
                for (const auto& tag : ingredient.tags) {
                    if (tag.find('|') != std::string::npos)
                        throw InputError("<csv>", "ingredient '" + ingredient.name + "'.tags",
                                         "tag '" + tag + "' contains '|', the CSV tag separator; use JSON");
                    tags += (tags.empty() ? "" : "|") + tag;
                }
                own[column] = tags;
            } else if (json.contains(column)) {
                own[column] = json.at(std::string(column)).get<std::string>();
            }
        }
        for (const auto column : kNumberColumns) {
            const auto& from = isLimit(column) ? json.at("limits") : json;
            if (from.contains(column))
                own[column] = io::csvNumber(from.at(std::string(column)).get<double>());
        }
        const auto record = [&](const std::vector<std::string>& spectrum_fields) {
            std::vector<std::string> fields;
            for (const auto column : columns) {
                const auto found = own.find(column);
                fields.push_back(found != own.end() ? found->second : std::string());
            }
            std::copy(spectrum_fields.begin(), spectrum_fields.end(), fields.end() - 6);
            out += io::csvLine(fields);
        };
        const auto& spectra = json.at("spectra");
        if (spectra.empty()) record({"", "", "", "", "", ""});
        for (const auto& [key, spectrum] : spectra.items()) {
            const std::string unit = spectrum.at("unit").get<std::string>();
            const std::string spectrum_source = spectrum.at("source").get<std::string>();
            const std::string date = spectrum.contains("date") ? spectrum.at("date").get<std::string>() : "";
            const auto wavelengths = spectrum.at("wavelengths_nm").get<std::vector<double>>();
            const auto values = spectrum.at("values").get<std::vector<double>>();
            for (std::size_t i = 0; i < values.size(); ++i) {
                // A constant spectrum is written without its (ignored) wavelength.
                const bool constant =
                    values.size() == 1 && wavelengths[0] == Spectrum(0.0).wavelengthsNm()[0];
                record({key, unit, spectrum_source, date, constant ? "" : io::csvNumber(wavelengths[i]),
                        io::csvNumber(values[i])});
            }
        }
    }
    return out;
}

}  // namespace paintlab::db
