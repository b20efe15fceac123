// Production sheets as CSV, JSON and printable HTML (production.h).

#include "paintlab/database/production.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace paintlab::db {

namespace {

using nlohmann::ordered_json;

ordered_json optionalJson(const std::optional<double>& value) {
    return value ? ordered_json(*value) : ordered_json(nullptr);
}

// Fixed decimals for people (the JSON and CSV carry full precision).
std::string fixed(double value, int decimals) { return io::formatFixed(value, decimals); }

std::string fixed(const std::optional<double>& value, int decimals) {
    return value ? fixed(*value, decimals) : std::string("n/a");
}

std::string html(std::string_view text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&#39;";
            break;
        default:
            out.push_back(c);
        }
    }
    return out;
}

std::string basis(const ProductionSheet& sheet) {
    const auto& o = sheet.options;
    if (o.batch_kg) return fixed(*o.batch_kg, 3) + " kg of wet paint per layer";
    return fixed(*o.area_m2, 3) + " m² painted at the dry film thickness, transfer efficiency " +
           fixed(o.transfer_efficiency, 2);
}

}  // namespace

std::string productionCsv(const ProductionSheet& sheet) {
    using io::csvLine;
    using io::csvNumber;
    std::string out =
        csvLine({"recipe", "version", "checksum_sha256", "layer_position", "layer", "dry_film_thickness_um",
                 "wet_film_thickness_um", "pigment_volume_concentration", "solids_mass_fraction",
                 "solids_volume_fraction", "batch_mass_kg", "kind", "ingredient", "density_g_cm3",
                 "binder_solids_mass_fraction", "dry_volume_fraction", "dry_mass_fraction",
                 "wet_mass_fraction", "mass_kg"});
    for (std::size_t i = 0; i < sheet.layers.size(); ++i) {
        const auto& layer = sheet.layers[i];
        for (const auto& line : layer.lines)
            out +=
                csvLine({sheet.version.recipe_name, std::to_string(sheet.version.version),
                         sheet.version.checksum_sha256, std::to_string(i + 1), layer.name,
                         csvNumber(layer.dry_film_thickness_um), csvNumber(layer.wet_film_thickness_um),
                         csvNumber(layer.pigment_volume_concentration), csvNumber(layer.solids_mass_fraction),
                         csvNumber(layer.solids_volume_fraction), csvNumber(layer.batch_mass_kg), line.kind,
                         line.name, csvNumber(line.density_g_cm3), csvNumber(line.solids_mass_fraction),
                         csvNumber(line.dry_volume_fraction), csvNumber(line.dry_mass_fraction),
                         csvNumber(line.wet_mass_fraction), csvNumber(line.mass_kg)});
    }
    return out;
}

std::string productionJson(const ProductionSheet& sheet) {
    ordered_json out{{"format", "paintlab-production"},
                     {"format_version", 1},
                     {"recipe", sheet.version.recipe_name},
                     {"version", sheet.version.version},
                     {"checksum_sha256", sheet.version.checksum_sha256},
                     {"author", sheet.version.author},
                     {"saved_at", sheet.version.created_at},
                     {"note", sheet.version.note},
                     {"substrate", sheet.substrate}};
    out["batch"] = {{"mass_kg_per_layer", optionalJson(sheet.options.batch_kg)},
                    {"area_m2", optionalJson(sheet.options.area_m2)},
                    {"transfer_efficiency", sheet.options.transfer_efficiency}};
    out["layers"] = ordered_json::array();
    for (const auto& layer : sheet.layers) {
        ordered_json l{{"name", layer.name},
                       {"dry_film_thickness_um", layer.dry_film_thickness_um},
                       {"wet_film_thickness_um", optionalJson(layer.wet_film_thickness_um)},
                       {"pigment_volume_concentration", layer.pigment_volume_concentration},
                       {"solids_mass_fraction", layer.solids_mass_fraction},
                       {"solids_volume_fraction", optionalJson(layer.solids_volume_fraction)},
                       {"dry_film_density_g_cm3", layer.dry_film_density_g_cm3},
                       {"wet_density_g_cm3", optionalJson(layer.wet_density_g_cm3)},
                       {"coating_weight_g_m2", layer.coating_weight_g_m2},
                       {"spreading_rate_m2_kg", layer.spreading_rate_m2_kg},
                       {"batch_mass_kg", layer.batch_mass_kg}};
        l["ingredients"] = ordered_json::array();
        for (const auto& line : layer.lines) {
            ordered_json i{{"kind", line.kind},
                           {"name", line.name},
                           {"density_g_cm3", line.density_g_cm3},
                           {"density_source", line.density_source},
                           {"dry_volume_fraction", line.dry_volume_fraction},
                           {"dry_mass_fraction", line.dry_mass_fraction},
                           {"wet_mass_fraction", line.wet_mass_fraction},
                           {"mass_kg", line.mass_kg}};
            if (line.kind == "binder") {
                i["solids_mass_fraction"] = optionalJson(line.solids_mass_fraction);
                i["solids_stored"] = line.solids_stored;
                i["volatile_density_g_cm3"] = optionalJson(line.volatile_density_g_cm3);
            }
            l["ingredients"].push_back(std::move(i));
        }
        l["warnings"] = layer.warnings;
        out["layers"].push_back(std::move(l));
    }
    return out.dump(2) + "\n";
}

std::string productionHtml(const ProductionSheet& sheet) {
    const auto& v = sheet.version;
    std::string out =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Production recipe: " +
        html(v.recipe_name) + " v" + std::to_string(v.version) + "</title>\n";
    out += "<style>\nbody { font-family: sans-serif; margin: 2em; }\n"
           "table { border-collapse: collapse; margin-bottom: 1.5em; }\n"
           "th, td { border: 1px solid #888; padding: 0.3em 0.6em; text-align: right; }\n"
           "th:first-child, td:first-child, td.text { text-align: left; }\n"
           ".checksum { font-family: monospace; word-break: break-all; }\n"
           ".warning { color: #a00; }\n"
           "@media print { body { margin: 0; } section { page-break-inside: avoid; } "
           "}\n</style>\n</head>\n<body>\n";
    out += "<h1>Production recipe: " + html(v.recipe_name) + "</h1>\n<table>\n";
    out += "<tr><td>Recipe version</td><td class=\"text\">" + std::to_string(v.version) + "</td></tr>\n";
    out += "<tr><td>SHA-256 of the version</td><td class=\"text checksum\">" + html(v.checksum_sha256) +
           "</td></tr>\n";
    out += "<tr><td>Saved</td><td class=\"text\">" + html(v.created_at) + " by " + html(v.author) +
           "</td></tr>\n";
    if (!v.note.empty()) out += "<tr><td>Note</td><td class=\"text\">" + html(v.note) + "</td></tr>\n";
    out += "<tr><td>Batch</td><td class=\"text\">" + html(basis(sheet)) + "</td></tr>\n";
    out += "<tr><td>Substrate</td><td class=\"text\">" + html(sheet.substrate) +
           " (not produced)</td></tr>\n</table>\n";
    for (std::size_t i = 0; i < sheet.layers.size(); ++i) {
        const auto& layer = sheet.layers[i];
        out += "<section>\n<h2>Layer " + std::to_string(i + 1) + ": " + html(layer.name) + "</h2>\n";
        out += "<p>Dry film thickness " + fixed(layer.dry_film_thickness_um, 1) + " µm, wet film thickness " +
               fixed(layer.wet_film_thickness_um, 1) + " µm; PVC " +
               fixed(100.0 * layer.pigment_volume_concentration, 2) + " %; solids " +
               fixed(100.0 * layer.solids_mass_fraction, 1) + " % by mass, " +
               (layer.solids_volume_fraction ? fixed(100.0 * *layer.solids_volume_fraction, 1)
                                             : std::string("n/a")) +
               " % by volume; coating weight " + fixed(layer.coating_weight_g_m2, 1) + " g/m²; batch " +
               fixed(layer.batch_mass_kg, 3) + " kg of wet paint.</p>\n";
        out += "<table>\n<tr><th>Ingredient</th><th>Kind</th><th>Density g/cm³</th><th>Dry vol. %</th>"
               "<th>Dry mass %</th><th>Wet mass %</th><th>Mass g</th><th>Weighed</th></tr>\n";
        for (const auto& line : layer.lines) {
            // The printable sheet is read by people: "interference flake", not the code.
            std::string kind = line.kind;
            std::replace(kind.begin(), kind.end(), '_', ' ');
            out += "<tr><td>" + html(line.name) + "</td><td class=\"text\">" + html(kind) + "</td><td>" +
                   fixed(line.density_g_cm3, 3) + "</td><td>" + fixed(100.0 * line.dry_volume_fraction, 2) +
                   "</td><td>" + fixed(100.0 * line.dry_mass_fraction, 2) + "</td><td>" +
                   fixed(100.0 * line.wet_mass_fraction, 2) + "</td><td>" + fixed(1000.0 * line.mass_kg, 2) +
                   "</td><td>&#9744;</td></tr>\n";
        }
        out += "</table>\n";
        for (const auto& line : layer.lines)
            if (line.kind == "binder")
                out +=
                    "<p>Binder weighed as bought: " +
                    fixed(100.0 * line.solids_mass_fraction.value_or(1.0), 1) + " % solids by mass" +
                    (line.solids_stored ? std::string() : std::string(" (no solids content stored for it)")) +
                    (line.volatile_density_g_cm3
                         ? ", volatile part " + fixed(*line.volatile_density_g_cm3, 3) + " g/cm³"
                         : std::string()) +
                    ".</p>\n";
        for (const auto& warning : layer.warnings)
            out += "<p class=\"warning\">Warning: " + html(warning) + "</p>\n";
        out += "</section>\n";
    }
    out += "<p>Masses from the dry-film volume fractions and densities: m_j = &phi;_j &rho;_j per cm³ of dry "
           "film, "
           "binder as bought m_b / s; volumes additive. Generated by PaintLab.</p>\n</body>\n</html>\n";
    return out;
}

}  // namespace paintlab::db
