// Production sheets (production.h): the masses to weigh in per layer, from a
// saved recipe version and the densities and binder solids in the database.

#include "paintlab/database/production.h"

#include "paintlab/database/ingredients.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/recipe_paths.h"

#include <cmath>

namespace paintlab::db {

namespace {

using io::formatNumber;

// The ingredient of a recipe row, with a density: the one the version was
// linked to when saved, or, for a row saved unlinked, the ingredient of that
// kind and name added to the database since (versions are immutable, so
// their links are never filled in later).
Ingredient linkedIngredient(Database& db, const std::optional<std::int64_t>& id, IngredientKind kind,
                            const std::string& name, const std::string& label) {
    const std::string file = db.file().string();
    std::optional<Ingredient> ingredient;
    if (id)
        ingredient = readIngredient(db, *id);
    else
        ingredient = findIngredient(db, kind, name);
    if (!ingredient)
        throw InputError(file, label,
                         "not in the database, so its density is unknown; add the " +
                             std::string(ingredientKindName(kind)) + " '" + name + "' first");
    if (!ingredient->density_g_cm3)
        throw InputError(file, label,
                         "the ingredient has no density (density_g_cm3); set one to compute its mass");
    return std::move(*ingredient);
}

void checkLimits(const Ingredient& ingredient, double volume_fraction, double thickness_um,
                 const std::string& label, std::vector<std::string>& warnings) {
    const auto& limits = ingredient.limits;
    if (limits.max_volume_fraction && volume_fraction > *limits.max_volume_fraction)
        warnings.push_back(label + ": volume fraction " + formatNumber(volume_fraction) +
                           " is above its technological maximum " +
                           formatNumber(*limits.max_volume_fraction));
    if (limits.min_thickness_um && thickness_um < *limits.min_thickness_um)
        warnings.push_back(label + ": dry film thickness " + formatNumber(thickness_um) +
                           " µm is below its minimum " + formatNumber(*limits.min_thickness_um) + " µm");
    if (limits.max_thickness_um && thickness_um > *limits.max_thickness_um)
        warnings.push_back(label + ": dry film thickness " + formatNumber(thickness_um) +
                           " µm is above its maximum " + formatNumber(*limits.max_thickness_um) + " µm");
}

}  // namespace

void validateProductionOptions(const ProductionOptions& options) {
    if (options.batch_kg.has_value() == options.area_m2.has_value())
        throw InputError("<argument>", "--batch-kg/--area-m2",
                         "give exactly one of the batch mass and the painted area");
    if (options.batch_kg && !(std::isfinite(*options.batch_kg) && *options.batch_kg > 0.0))
        throw InputError("<argument>", "--batch-kg", formatNumber(*options.batch_kg) + " kg: must be > 0");
    if (options.area_m2 && !(std::isfinite(*options.area_m2) && *options.area_m2 > 0.0))
        throw InputError("<argument>", "--area-m2", formatNumber(*options.area_m2) + " m2: must be > 0");
    if (!(options.transfer_efficiency > 0.0 && options.transfer_efficiency <= 1.0))
        throw InputError("<argument>", "--transfer-efficiency",
                         formatNumber(options.transfer_efficiency) + " is outside 0 (exclusive) to 1");
}

ProductionSheet productionSheet(Database& db, std::string_view recipe_name, std::optional<int> version,
                                const ProductionOptions& options) {
    validateProductionOptions(options);
    const StoredRecipeVersion stored = loadRecipeVersion(db, recipe_name, version);
    const std::string file = db.file().string();
    ProductionSheet sheet;
    sheet.version = stored.info;
    sheet.substrate = std::string(substrateKind(stored.recipe.substrate));
    sheet.options = options;
    for (std::size_t i = 0; i < stored.recipe.layers.size(); ++i) {
        const Layer& layer = stored.recipe.layers[i];
        const LayerLink& link = stored.layers.at(i);
        ProductionLayer out;
        out.name = layer.name;
        out.dry_film_thickness_um = layer.thickness_um;
        const double t = layer.thickness_um;

        // Per cm3 of dry film: masses m_j = phi_j rho_j (production.h).
        double phi_components = 0.0;
        double m_components = 0.0;
        for (std::size_t j = 0; j < layer.components.size(); ++j) {
            const Component& component = layer.components[j];
            const std::string kind(componentKind(component));
            const std::string component_label =
                ingredientLabel(componentPath(i, j), kind, componentName(component));
            if (std::holds_alternative<RawMedium>(component))
                throw InputError(
                    file, component_label,
                    "a raw medium is given by its optical thickness, not a composition: it has no "
                    "production recipe");
            const Ingredient ingredient =
                linkedIngredient(db, link.components.at(j).ingredient_id,
                                 parseIngredientKind(kind).value_or(IngredientKind::Pigment),
                                 componentName(component), component_label);
            const double phi = componentVolumeFraction(component);
            ProductionLine line;
            line.kind = kind;
            line.name = componentName(component);
            line.density_g_cm3 = *ingredient.density_g_cm3;
            line.density_source = ingredient.density_source;
            line.dry_volume_fraction = phi;
            line.wet_mass_fraction = phi * line.density_g_cm3;  // m_j for now
            checkLimits(ingredient, phi, t, component_label, out.warnings);
            phi_components += phi;
            m_components += line.wet_mass_fraction;
            out.lines.push_back(std::move(line));
        }
        const std::string binder_label = ingredientLabel(binderPath(i), "binder", layer.binder.name);
        const Ingredient binder = linkedIngredient(db, link.binder_ingredient_id, IngredientKind::Binder,
                                                   layer.binder.name, binder_label);
        const double phi_b = 1.0 - phi_components;
        const double rho_b = *binder.density_g_cm3;
        const double s = binder.solids_mass_fraction.value_or(1.0);
        const double m_b = phi_b * rho_b;
        const double m_b_in = m_b / s;
        const double m_v = m_b_in - m_b;
        std::optional<double> V_v;
        if (binder.volatile_density_g_cm3)
            V_v = m_v / *binder.volatile_density_g_cm3;
        else if (m_v == 0.0)
            V_v = 0.0;
        checkLimits(binder, phi_b, t, binder_label, out.warnings);

        const double m_dry = m_components + m_b;
        const double m_wet = m_components + m_b_in;
        out.pigment_volume_concentration = phi_components;
        out.dry_film_density_g_cm3 = m_dry;
        out.wet_mass_per_dry_volume_g_cm3 = m_wet;
        out.solids_mass_fraction = m_dry / m_wet;
        if (V_v) {
            out.solids_volume_fraction = 1.0 / (1.0 + *V_v);
            out.wet_film_thickness_um = t / *out.solids_volume_fraction;
            out.wet_density_g_cm3 = m_wet / (1.0 + *V_v);
        }
        out.coating_weight_g_m2 = m_dry * t;
        out.spreading_rate_m2_kg = 1000.0 / (t * m_wet);
        out.batch_mass_kg = options.batch_kg
                                ? *options.batch_kg
                                : *options.area_m2 * t * m_wet / 1000.0 / options.transfer_efficiency;

        ProductionLine binder_line;
        binder_line.kind = "binder";
        binder_line.name = layer.binder.name;
        binder_line.density_g_cm3 = rho_b;
        binder_line.density_source = binder.density_source;
        binder_line.dry_volume_fraction = phi_b;
        binder_line.wet_mass_fraction = m_b_in;
        binder_line.solids_mass_fraction = s;
        binder_line.solids_stored = binder.solids_mass_fraction.has_value();
        binder_line.volatile_density_g_cm3 = binder.volatile_density_g_cm3;
        out.lines.insert(out.lines.begin(), std::move(binder_line));
        for (auto& line : out.lines) {
            const double dry_mass = line.kind == "binder" ? m_b : line.wet_mass_fraction;
            line.dry_mass_fraction = dry_mass / m_dry;
            line.wet_mass_fraction /= m_wet;
            line.mass_kg = out.batch_mass_kg * line.wet_mass_fraction;
        }
        sheet.layers.push_back(std::move(out));
    }
    return sheet;
}

}  // namespace paintlab::db
