#pragma once
// Production recipes: how much of every ingredient to weigh in for a batch
// of each layer's paint, from a saved recipe version.
//
// A recipe describes the dry film: per layer its dry film thickness t (µm)
// and the volume fraction phi_j of every pigment and flake; the binder
// solids fill the rest, phi_b = 1 - sum_j phi_j. The database adds the
// densities rho (g/cm3; a binder's is that of its dry film) and, for the
// binder as bought, its solids mass fraction s (non-volatile content) and
// the density rho_v of its volatile part. Per cm3 of dry film (volumes
// additive, no loss on drying besides the volatiles):
//
//   m_j     = phi_j rho_j                       g of pigment or flake j
//   m_b     = phi_b rho_b                       g of binder solids
//   m_b,in  = m_b / s                           g of binder as bought (solution)
//   m_v     = m_b,in - m_b                      g of volatiles; V_v = m_v / rho_v cm3
//   m_dry   = sum_j m_j + m_b                   g of dry film (= its density, g/cm3)
//   m_wet   = sum_j m_j + m_b,in                g of wet paint
//   NV      = m_dry / m_wet                     solids by mass of the wet paint
//   VS      = 1 / (1 + V_v)                     solids by volume (needs rho_v)
//   PVC     = sum_j phi_j                       pigment (and flake) volume concentration
//   WFT     = t / VS                            wet film thickness, µm
//
// Batch by mass: M kg of wet paint per layer; ingredient j gets M m_j / m_wet
// and the binder M m_b,in / m_wet, so the masses add up to M.
// Batch by painted area: A m2 at the layer's dry film thickness holds
// V_dry = A t cm3 of dry film (1 m2 x 1 µm = 1 cm3), i.e. M = A t m_wet / 1000 kg,
// divided by the transfer efficiency of the application (1 = no overspray).
// Coating weight m_dry t g/m2; theoretical spreading rate 1000 / (t m_wet) m2/kg.

#include "paintlab/database/database.h"
#include "paintlab/database/recipes.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

struct ProductionOptions {
    std::optional<double> batch_kg;    // wet paint per layer; exactly one of batch_kg and area_m2
    std::optional<double> area_m2;     // painted area
    double transfer_efficiency = 1.0;  // (0, 1]; with area_m2
};

struct ProductionLine {
    std::string kind;  // "binder", "pigment", "mirror_flake", "interference_flake"
    std::string name;
    double density_g_cm3 = 0.0;
    double dry_volume_fraction = 0.0;            // in the dry film (binder: its solids)
    double dry_mass_fraction = 0.0;              // in the dry film
    double wet_mass_fraction = 0.0;              // of the wet paint, as weighed in
    double mass_kg = 0.0;                        // to weigh in (binder: as bought, volatiles included)
    std::optional<double> solids_mass_fraction;  // binder: s as used (unset in the database: 1)
    bool solids_stored = false;                  // binder: s came from the database, not the default 1
    std::optional<double> volatile_density_g_cm3;
    std::string density_source;
};

struct ProductionLayer {
    std::string name;
    double dry_film_thickness_um = 0.0;
    std::optional<double> wet_film_thickness_um;  // needs the binder's volatile density (or s = 1)
    double pigment_volume_concentration = 0.0;
    double solids_mass_fraction = 0.0;             // NV
    std::optional<double> solids_volume_fraction;  // VS
    double dry_film_density_g_cm3 = 0.0;
    double wet_mass_per_dry_volume_g_cm3 = 0.0;  // m_wet
    std::optional<double> wet_density_g_cm3;     // m_wet / (1 + V_v)
    double batch_mass_kg = 0.0;
    double coating_weight_g_m2 = 0.0;
    double spreading_rate_m2_kg = 0.0;
    std::vector<ProductionLine> lines;  // binder first, then the components in recipe order
    std::vector<std::string> warnings;  // technological limits exceeded
};

struct ProductionSheet {
    RecipeVersionInfo version;
    std::string substrate;  // what the paint goes on (not produced)
    ProductionOptions options;
    std::vector<ProductionLayer> layers;  // top first, as in the recipe
};

// Validates the options (InputError naming "<argument>" and the option).
void validateProductionOptions(const ProductionOptions& options);

// The sheet of a saved recipe version (the latest if version is unset),
// with the ingredients the version links to (a component saved unlinked is
// looked up by kind and name, in case it was added since). Throws InputError
// naming the database file and the layer and ingredient when an ingredient
// is not in the database, has no density, or a layer holds a raw medium
// (no composition).
ProductionSheet productionSheet(Database& db, std::string_view recipe_name, std::optional<int> version,
                                const ProductionOptions& options);

// The sheet as CSV (one record per ingredient line, layer totals in the
// columns), JSON, and a printable HTML page naming the recipe, its version
// and its SHA-256 checksum.
std::string productionCsv(const ProductionSheet& sheet);
std::string productionJson(const ProductionSheet& sheet);
std::string productionHtml(const ProductionSheet& sheet);

}  // namespace paintlab::db
