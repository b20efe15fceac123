// Database measurements as fit observations, and fit results as `fit` rows
// (fit_observations.h).

#include "paintlab/database/fit_observations.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace paintlab::db {

namespace {

fit::MultiAngleMeasurement multiAngle(const Measurement& m, fit::Side side) {
    fit::MultiAngleMeasurement out;
    out.name = m.name;
    out.side = side;
    out.illuminant = measurementIlluminant(m);
    out.observer = measurementObserver(m);
    for (const auto& r : m.readings) {
        fit::MultiAngleReading reading;
        reading.illumination_deg = r.illumination_deg;
        reading.aspecular_deg = r.aspecular_deg;
        reading.azimuth_deg = r.azimuth_deg;
        if (!r.reflectance.empty()) {
            reading.wavelengths_nm = m.wavelengths_nm;
            reading.reflectance_factor = r.reflectance;
        }
        reading.lab = Lab{r.L, r.a, r.b};
        out.readings.push_back(std::move(reading));
    }
    return out;
}

fit::BrdfMeasurement brdf(const Measurement& m, fit::Side side) {
    fit::BrdfMeasurement out;
    out.name = m.name;
    out.side = side;
    // The fitter takes RGB as R, G, B; a file may order its columns otherwise.
    std::array<std::size_t, 3> order{0, 1, 2};
    if (!m.channels.empty()) {
        out.values = fit::BrdfValues::LinearSrgb;
        const std::array<const char*, 3> names{"R", "G", "B"};
        if (m.channels.size() != 3)
            throw InputError(m.name, "channels", "a fit takes RGB samples as the three channels R, G and B");
        for (std::size_t c = 0; c < 3; ++c) {
            const auto at = std::find(m.channels.begin(), m.channels.end(), names[c]);
            if (at == m.channels.end())
                throw InputError(m.name, "channels",
                                 std::string("no channel ") + names[c] +
                                     " (a fit takes RGB samples as linear sRGB R, G, B)");
            order[c] = static_cast<std::size_t>(at - m.channels.begin());
        }
    } else {
        out.values = fit::BrdfValues::Spectral;
        out.wavelengths_nm = m.wavelengths_nm;
    }
    for (const auto& s : m.samples) {
        fit::BrdfSample sample{s.theta_i_deg, s.phi_i_deg, s.theta_o_deg, s.phi_o_deg, {}, 0.0};
        if (out.values == fit::BrdfValues::LinearSrgb)
            for (const std::size_t c : order) sample.values.push_back(s.values.at(c));
        else
            sample.values = s.values;
        out.samples.push_back(std::move(sample));
    }
    return out;
}

}  // namespace

void addFitObservation(fit::Observations& observations, const Measurement& measurement, fit::Side side) {
    if (measurement.kind == MeasurementKind::MultiAngle)
        observations.multi_angle.push_back(multiAngle(measurement, side));
    else
        observations.brdf.push_back(brdf(measurement, side));
}

std::vector<Fit> fitRecords(const fit::FitResult& result, const fit::FitProblem& problem,
                            const std::string& recipe_name, int recipe_version, const std::string& note) {
    const fit::FitSettings& settings = problem.settings;
    Fit common;
    common.recipe_name = recipe_name;
    common.recipe_version = recipe_version;
    common.method = "fast model, Ceres multi-start (" + std::to_string(settings.starts) + " starts, " +
                    std::string(presetName(settings.search_preset)) + " search, " +
                    std::string(presetName(settings.polish_preset)) + " polish)";
    if (result.residual_count > 0)
        common.residual_rms = std::sqrt(2.0 * result.cost / static_cast<double>(result.residual_count));
    for (const auto& p : result.parameters) {
        common.parameters[p.path] = p.value;
        if (std::isfinite(p.sigma)) common.parameters[p.path + ".sigma"] = p.sigma;
    }
    common.note = note;
    std::vector<Fit> rows;
    for (std::size_t m = 0; m < problem.observations.multi_angle.size(); ++m) {
        Fit row = common;
        row.measurement_name = problem.observations.multi_angle[m].name;
        for (const auto& g : result.geometries)
            if (g.measurement == m) row.residuals.push_back(g.delta_e00);
        rows.push_back(std::move(row));
    }
    for (std::size_t m = 0; m < problem.observations.brdf.size(); ++m) {
        Fit row = common;
        row.measurement_name = problem.observations.brdf[m].name;
        for (const auto& r : result.residuals)
            if (r.kind == fit::ObservationKind::BrdfSample && r.measurement == m)
                row.residuals.push_back(r.log_error);
        rows.push_back(std::move(row));
    }
    return rows;
}

}  // namespace paintlab::db
