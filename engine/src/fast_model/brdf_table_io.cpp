// The tabulated-BRDF file, JSON and CSV (fast_model/brdf_table_io.h).

#include "paintlab/engine/fast_model/brdf_table_io.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/montecarlo/mc_table.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

namespace paintlab {

namespace {

using nlohmann::ordered_json;

std::vector<double> angleGrid(double step, double last) {
    std::vector<double> grid;
    for (double a = 0.0; a <= last + 1e-9; a += step) grid.push_back(a);
    return grid;
}

// Standard error of eval from the spread of the per-batch tables (mc_table.h, batchEstimate).
void batchStdError(const std::vector<LayeredBrdf>& batches, const Direction& wi, const Direction& wo,
                   std::vector<double>& se) {
    std::vector<std::vector<double>> values;
    values.reserve(batches.size());
    for (const auto& b : batches) values.push_back(b.eval(wi, wo));
    for (std::size_t k = 0; k < se.size(); ++k) {
        std::vector<double> column;
        column.reserve(values.size());
        for (const auto& v : values) column.push_back(v[k]);
        se[k] = mc::batchEstimate(column).std_error;
    }
}

// CSV numbers keep 6 significant digits (the table's format since it was first written).
std::string csvValue(double value) { return io::formatNumber(value, io::NumberFormat::Message); }

ordered_json settingsObject(std::string_view settings_json) {
    ordered_json settings = ordered_json::parse(settings_json, nullptr, false);
    if (!settings.is_object()) throw Error("brdf table: the settings are not the text of a JSON object");
    return settings;
}

}  // namespace

bool isBrdfTableCsvPath(std::string_view path) { return path.size() > 4 && path.ends_with(".csv"); }

std::string brdfTableText(const LayeredBrdf& brdf, const std::string& recipe_path,
                          std::string_view settings_json, double step_deg, bool csv,
                          const std::vector<LayeredBrdf>* batches) {
    if (!(step_deg >= 0.5 && step_deg <= 45.0))
        throw InputError("<argument>", "--step", "must be between 0.5 and 45 degrees");
    const auto wavelengths = brdf.wavelengthsNm();
    // Regular grid: incidence and exit 0..85 deg, azimuth difference 0..180 deg
    // (the paint is isotropic, so f depends on phi_o - phi_i only, symmetrically).
    const auto thetas = angleGrid(step_deg, 85.0);
    const auto phis = angleGrid(step_deg, 180.0);
    std::string text;
    std::vector<std::string> row;
    if (csv) {
        row = {"theta_i_deg", "theta_o_deg", "phi_deg"};
        for (double nm : wavelengths) row.push_back("f_" + csvValue(nm) + "nm_per_sr");
        if (batches != nullptr)
            for (double nm : wavelengths) row.push_back("se_" + csvValue(nm) + "nm_per_sr");
        text += io::csvJoin(row);
    }
    ordered_json values = ordered_json::array();
    ordered_json errors = ordered_json::array();
    std::vector<double> se(wavelengths.size());
    for (double ti : thetas) {
        ordered_json by_to = ordered_json::array();
        ordered_json se_by_to = ordered_json::array();
        for (double to : thetas) {
            ordered_json by_phi = ordered_json::array();
            ordered_json se_by_phi = ordered_json::array();
            for (double phi : phis) {
                const Direction wi = directionFromAnglesDeg(ti, 0.0);
                const Direction wo = directionFromAnglesDeg(to, phi);
                const auto f = brdf.eval(wi, wo);
                if (batches != nullptr) batchStdError(*batches, wi, wo, se);
                if (csv) {
                    row = {csvValue(ti), csvValue(to), csvValue(phi)};
                    for (double v : f) row.push_back(csvValue(v));
                    if (batches != nullptr)
                        for (double v : se) row.push_back(csvValue(v));
                    text += io::csvJoin(row);
                } else {
                    by_phi.push_back(f);
                    if (batches != nullptr) se_by_phi.push_back(se);
                }
            }
            if (!csv) {
                by_to.push_back(std::move(by_phi));
                se_by_to.push_back(std::move(se_by_phi));
            }
        }
        if (!csv) {
            values.push_back(std::move(by_to));
            errors.push_back(std::move(se_by_to));
        }
    }
    if (!csv) {
        ordered_json out;
        out["recipe"] = recipe_path;
        out["settings"] = settingsObject(settings_json);
        out["wavelengths_nm"] = std::vector<double>(wavelengths.begin(), wavelengths.end());
        out["theta_i_deg"] = thetas;
        out["theta_o_deg"] = thetas;
        out["phi_deg"] = phis;
        out["brdf_per_sr"] = std::move(values);  // [theta_i][theta_o][phi][band], mirror term excluded
        if (batches != nullptr) out["brdf_std_error_per_sr"] = std::move(errors);
        ordered_json specular = ordered_json::array();
        for (double ti : thetas)
            specular.push_back(brdf.specularReflectance(std::cos(ti * std::numbers::pi / 180.0)));
        out["specular_reflectance"] =
            std::move(specular);  // [theta_i][band], the top interface's mirror term
        text += out.dump(1);
        text += '\n';
    }
    return text;
}

}  // namespace paintlab
