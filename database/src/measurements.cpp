// Measurements and fits (measurements.h): one row each; a measurement's
// data are JSON in measurement.data_json (measurement_json.h).

#include "paintlab/database/measurements.h"

#include "measurement_json.h"
#include "sqlite.h"

#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <span>

namespace paintlab::db {

namespace {

using detail::Connection;
using detail::Statement;
using detail::Transaction;

using io::formatNumber;

void requireFinite(double value, const std::string& source, const std::string& field) {
    if (!std::isfinite(value)) throw InputError(source, field, "not a finite number");
}

void requireRange(double value, double min, double max, const std::string& source, const std::string& field,
                  const char* unit) {
    requireFinite(value, source, field);
    if (value < min || value > max)
        throw InputError(source, field,
                         formatNumber(value) + " " + unit + " is outside " + formatNumber(min) + " to " +
                             formatNumber(max));
}

std::optional<std::int64_t> measurementId(const Connection& c, std::string_view name) {
    Statement s(c, "SELECT id FROM measurement WHERE name = ?1 ORDER BY id LIMIT 1");
    s.bind(1, name);
    if (!s.step()) return std::nullopt;
    return s.integer(0);
}

constexpr const char* kFitColumns =
    "SELECT f.id, r.name, v.version, m.name, f.method, f.residual_rms, f.residuals_json, f.parameters_json, "
    "f.note, f.created_at FROM fit f JOIN recipe_version v ON v.id = f.recipe_version_id "
    "JOIN recipe r ON r.id = v.recipe_id JOIN measurement m ON m.id = f.measurement_id ";

std::vector<Fit> readFits(const Connection& c, Statement& s) {
    std::vector<Fit> out;
    while (s.step()) {
        Fit fit;
        fit.id = s.integer(0);
        fit.recipe_name = s.text(1);
        fit.recipe_version = static_cast<int>(s.integer(2));
        fit.measurement_name = s.text(3);
        fit.method = s.text(4);
        fit.residual_rms = s.optionalReal(5);
        try {
            fit.residuals = nlohmann::json::parse(s.text(6)).get<std::vector<double>>();
            fit.parameters = nlohmann::json::parse(s.text(7)).get<std::map<std::string, double>>();
        } catch (const std::exception& e) {
            throw DatabaseError(c.file(), DatabaseError::Reason::Corrupt,
                                "fit " + std::to_string(fit.id) +
                                    " has unreadable residuals or parameters: " + e.what());
        }
        fit.note = s.text(8);
        fit.created_at = s.text(9);
        out.push_back(std::move(fit));
    }
    return out;
}

void requireWavelengths(std::span<const double> wavelengths_nm, const std::string& source) {
    for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
        const std::string field = "wavelengths_nm[" + std::to_string(i) + "]";
        requireFinite(wavelengths_nm[i], source, field);
        if (wavelengths_nm[i] <= 0.0) throw InputError(source, field, "a wavelength must be positive");
        if (i > 0 && wavelengths_nm[i] <= wavelengths_nm[i - 1])
            throw InputError(source, field, "wavelengths must be strictly increasing");
    }
}

// A multi-angle reading's spectrum: one reflectance factor per wavelength, >= 0.
void requireReflectance(const MultiAngleReading& r, std::size_t wavelengths, const std::string& source,
                        const std::string& field) {
    if (r.reflectance.size() != wavelengths)
        throw InputError(source, field + ".reflectance",
                         std::to_string(r.reflectance.size()) + " values for " + std::to_string(wavelengths) +
                             " wavelengths" +
                             (wavelengths == 0 ? " (give wavelengths_nm with spectral readings)" : ""));
    for (std::size_t j = 0; j < r.reflectance.size(); ++j) {
        const std::string at = field + ".reflectance[" + std::to_string(j) + "]";
        requireFinite(r.reflectance[j], source, at);
        if (r.reflectance[j] < 0.0) throw InputError(source, at, "a reflectance factor cannot be negative");
    }
}

}  // namespace

namespace {

// A signed decimal number as geometry names write it: "-15", "+15", "_45",
// "minus15" (the last two for software that keeps '-' out of identifiers).
std::optional<double> geometryNumber(std::string_view text) {
    bool negative = false;
    if (text.starts_with("minus")) {
        negative = true;
        text.remove_prefix(5);
    } else if (!text.empty() && (text.front() == '-' || text.front() == '_' || text.front() == '+')) {
        negative = text.front() != '+';
        text.remove_prefix(1);
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || text.front() == '-' || error != std::errc() || end != text.data() + text.size() ||
        !std::isfinite(value))
        return std::nullopt;
    return negative ? -value : value;
}

}  // namespace

std::optional<MultiAngleGeometry> parseMultiAngleGeometry(std::string_view name) {
    std::string text;
    for (std::size_t i = 0; i < name.size(); ++i) {
        const auto c = static_cast<unsigned char>(name[i]);
        if (c == 0xC2 && i + 1 < name.size() && static_cast<unsigned char>(name[i + 1]) == 0xB0) {
            ++i;  // the degree sign in UTF-8
            continue;
        }
        if (std::isspace(c) != 0) continue;
        text.push_back(static_cast<char>(std::tolower(c)));
    }
    std::string_view rest = text;
    if (rest.starts_with("r")) rest.remove_prefix(1);  // X-Rite's "r" (reflectance) prefix
    const auto as = rest.find("as");
    if (as == std::string_view::npos || as == 0) return std::nullopt;
    MultiAngleGeometry g;
    const auto illumination = geometryNumber(rest.substr(0, as));
    if (!illumination || *illumination < 0.0) return std::nullopt;
    g.illumination_deg = *illumination;
    rest.remove_prefix(as + 2);
    const auto az = rest.find("az");
    const auto aspecular = geometryNumber(rest.substr(0, az));
    if (!aspecular) return std::nullopt;
    g.aspecular_deg = *aspecular;
    if (az != std::string_view::npos) {
        const auto azimuth = geometryNumber(rest.substr(az + 2));
        if (!azimuth) return std::nullopt;
        g.azimuth_deg = *azimuth;
    }
    return g;
}

std::string multiAngleGeometryName(double illumination_deg, double aspecular_deg, double azimuth_deg) {
    std::string name = formatNumber(illumination_deg, io::NumberFormat::Shortest) + "as" +
                       formatNumber(aspecular_deg, io::NumberFormat::Shortest);
    if (!isInPlane(azimuth_deg)) name += "az" + formatNumber(azimuth_deg, io::NumberFormat::Shortest);
    return name;
}

Illuminant measurementIlluminant(const Measurement& m) {
    if (m.illuminant == "D50") return Illuminant::D50;
    if (m.illuminant == "A") return Illuminant::A;
    return Illuminant::D65;
}

Observer measurementObserver(const Measurement& m) {
    return m.observer == "2deg" ? Observer::Cie1931_2deg : Observer::Cie1964_10deg;
}

std::string_view measurementKindName(MeasurementKind kind) {
    return kind == MeasurementKind::Brdf ? "brdf" : "multiangle";
}

std::optional<MeasurementKind> parseMeasurementKind(std::string_view name) {
    if (name == "brdf") return MeasurementKind::Brdf;
    if (name == "multiangle") return MeasurementKind::MultiAngle;
    return std::nullopt;
}

void labFromSpectra(Measurement& m, const std::string& source) {
    if (m.wavelengths_nm.empty()) return;
    const ColourConditions conditions{measurementIlluminant(m), measurementObserver(m)};
    for (std::size_t i = 0; i < m.readings.size(); ++i) {
        auto& r = m.readings[i];
        requireReflectance(r, m.wavelengths_nm.size(), source, "readings[" + std::to_string(i) + "]");
        const Lab lab = spectrumColour(m.wavelengths_nm, r.reflectance, conditions).lab;
        r.L = lab.L;
        r.a = lab.a;
        r.b = lab.b;
    }
}

void validateMeasurement(const Measurement& m, const std::string& source) {
    if (m.name.empty()) throw InputError(source, "name", "a measurement needs a name");
    if (m.kind == MeasurementKind::MultiAngle) {
        if (m.readings.empty()) throw InputError(source, "readings", "no reading");
        if (m.observer != "2deg" && m.observer != "10deg")
            throw InputError(source, "observer", "'" + m.observer + "' is not 2deg or 10deg");
        if (m.illuminant != "D65" && m.illuminant != "D50" && m.illuminant != "A")
            throw InputError(source, "illuminant", "'" + m.illuminant + "' is not D65, D50 or A");
        for (std::size_t i = 0; i < m.readings.size(); ++i) {
            const auto& r = m.readings[i];
            const std::string field = "readings[" + std::to_string(i) + "]";
            requireRange(r.illumination_deg, 0.0, 89.9, source, field + ".illumination_deg", "deg");
            requireRange(r.azimuth_deg, -180.0, 180.0, source, field + ".azimuth_deg", "deg");
            if (isInPlane(r.azimuth_deg)) {
                // The detector stays above the horizon: its polar angle |illumination - aspecular| < 90.
                requireRange(r.aspecular_deg, r.illumination_deg - kMaxDetectorPolarDeg,
                             r.illumination_deg + kMaxDetectorPolarDeg, source, field + ".aspecular_deg",
                             "deg");
            } else {
                requireFinite(r.aspecular_deg, source, field + ".aspecular_deg");
                if (const std::string problem = outOfPlaneFormProblem(r.aspecular_deg, r.azimuth_deg);
                    !problem.empty())
                    throw InputError(source, field + ".aspecular_deg", problem);
                const double polar = detectorPolarAngleDeg(
                    multiAngleDirections(r.illumination_deg, r.aspecular_deg, r.azimuth_deg));
                if (!(polar <= kMaxDetectorPolarDeg))
                    throw InputError(source, field + ".aspecular_deg",
                                     formatNumber(r.aspecular_deg) + " deg at azimuth " +
                                         formatNumber(r.azimuth_deg) + " deg puts the detector " +
                                         formatNumber(polar) + " deg from the normal (at most " +
                                         formatNumber(kMaxDetectorPolarDeg) + ")");
            }
            requireRange(r.L, 0.0, 400.0, source, field + ".L", "");
            requireFinite(r.a, source, field + ".a");
            requireFinite(r.b, source, field + ".b");
            if (!m.wavelengths_nm.empty() || !r.reflectance.empty())
                requireReflectance(r, m.wavelengths_nm.size(), source, field);
        }
        requireWavelengths(m.wavelengths_nm, source);
        if (!m.samples.empty() || !m.channels.empty())
            throw InputError(source, "samples", "a multiangle measurement has readings, not BRDF samples");
        return;
    }
    if (m.samples.empty()) throw InputError(source, "samples", "no BRDF sample");
    if (!m.readings.empty())
        throw InputError(source, "readings", "a BRDF measurement has samples, not readings");
    if (m.channels.empty() == m.wavelengths_nm.empty())
        throw InputError(source, "channels",
                         "give either channel names (R, G, B) or wavelengths_nm, not both");
    requireWavelengths(m.wavelengths_nm, source);
    for (const auto& channel : m.channels)
        if (channel.empty()) throw InputError(source, "channels", "a channel has no name");
    const std::size_t channels = m.channels.size() + m.wavelengths_nm.size();
    for (std::size_t i = 0; i < m.samples.size(); ++i) {
        const auto& s = m.samples[i];
        const std::string field = "samples[" + std::to_string(i) + "]";
        requireRange(s.theta_i_deg, 0.0, 90.0, source, field + ".theta_i_deg", "deg");
        requireRange(s.theta_o_deg, 0.0, 90.0, source, field + ".theta_o_deg", "deg");
        requireRange(s.phi_i_deg, -360.0, 360.0, source, field + ".phi_i_deg", "deg");
        requireRange(s.phi_o_deg, -360.0, 360.0, source, field + ".phi_o_deg", "deg");
        if (s.values.size() != channels)
            throw InputError(source, field + ".values",
                             std::to_string(s.values.size()) + " values for " + std::to_string(channels) +
                                 " channels");
        for (std::size_t j = 0; j < s.values.size(); ++j) {
            const std::string at = field + ".values[" + std::to_string(j) + "]";
            requireFinite(s.values[j], source, at);
            if (s.values[j] < 0.0) throw InputError(source, at, "a BRDF value cannot be negative");
        }
    }
}

std::int64_t createMeasurement(Database& db, const Measurement& measurement) {
    const Connection& c = db.impl().connection;
    const std::string file = c.file().string();
    validateMeasurement(measurement, file);
    Transaction transaction(c, Transaction::Mode::Write);
    if (measurementId(c, measurement.name))
        throw InputError(file, "measurement '" + measurement.name + "'",
                         "a measurement with this name already exists");
    Statement s(c,
                "INSERT INTO measurement (name, kind, instrument, geometry, sample, measured_at, data_json, "
                "source) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
    s.bind(1, measurement.name)
        .bind(2, measurementKindName(measurement.kind))
        .bind(3, measurement.instrument)
        .bind(4, measurement.geometry)
        .bind(5, measurement.sample)
        .bind(6, measurement.measured_at)
        .bind(7, detail::measurementJson(measurement, false).dump())
        .bind(8, measurement.source)
        .run();
    const std::int64_t id = c.lastInsertId();
    transaction.commit();
    return id;
}

std::optional<Measurement> findMeasurement(Database& db, std::string_view name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, "SELECT id, name, kind, instrument, geometry, sample, measured_at, data_json, source "
                   "FROM measurement WHERE name = ?1 ORDER BY id LIMIT 1");
    s.bind(1, name);
    if (!s.step()) return std::nullopt;
    Measurement m;
    m.id = s.integer(0);
    m.name = s.text(1);
    const auto kind = parseMeasurementKind(s.text(2));
    m.kind = kind.value_or(MeasurementKind::MultiAngle);
    m.instrument = s.text(3);
    m.geometry = s.text(4);
    m.sample = s.text(5);
    m.measured_at = s.text(6);
    m.source = s.text(8);
    const std::string label = c.file().string() + ": measurement '" + m.name + "'";
    try {
        detail::readMeasurementJson(nlohmann::json::parse(s.text(7)), false, m, label);
    } catch (const std::exception& e) {
        throw DatabaseError(c.file(), DatabaseError::Reason::Corrupt,
                            "measurement '" + m.name + "' has unreadable data: " + e.what());
    }
    transaction.commit();
    return m;
}

std::vector<MeasurementSummary> listMeasurements(Database& db) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, "SELECT m.id, m.name, m.kind, m.instrument, m.sample, m.measured_at, "
                   "coalesce(json_array_length(m.data_json, '$.readings'), json_array_length(m.data_json, "
                   "'$.samples'), 0), (SELECT count(*) FROM fit f WHERE f.measurement_id = m.id) "
                   "FROM measurement m ORDER BY m.name, m.id");
    std::vector<MeasurementSummary> out;
    while (s.step())
        out.push_back({s.integer(0), s.text(1),
                       parseMeasurementKind(s.text(2)).value_or(MeasurementKind::MultiAngle), s.text(3),
                       s.text(4), s.text(5), static_cast<std::size_t>(s.integer(6)),
                       static_cast<std::size_t>(s.integer(7))});
    transaction.commit();
    return out;
}

std::int64_t recordFit(Database& db, const Fit& fit) {
    const Connection& c = db.impl().connection;
    const std::string file = c.file().string();
    if (fit.residual_rms && !(std::isfinite(*fit.residual_rms) && *fit.residual_rms >= 0.0))
        throw InputError(file, "fit.residual_rms", "must be a finite number >= 0");
    for (std::size_t i = 0; i < fit.residuals.size(); ++i)
        requireFinite(fit.residuals[i], file, "fit.residuals[" + std::to_string(i) + "]");
    for (const auto& [key, value] : fit.parameters) requireFinite(value, file, "fit.parameters." + key);
    Transaction transaction(c, Transaction::Mode::Write);
    Statement version(c, "SELECT v.id FROM recipe_version v JOIN recipe r ON r.id = v.recipe_id "
                         "WHERE r.name = ?1 AND v.version = ?2");
    version.bind(1, fit.recipe_name).bind(2, fit.recipe_version);
    if (!version.step())
        throw InputError(file,
                         "recipe '" + fit.recipe_name + "' version " + std::to_string(fit.recipe_version),
                         "no such recipe version");
    const auto measurement = measurementId(c, fit.measurement_name);
    if (!measurement)
        throw InputError(file, "measurement '" + fit.measurement_name + "'", "no such measurement");
    Statement s(c,
                "INSERT INTO fit (recipe_version_id, measurement_id, method, residual_rms, residuals_json, "
                "parameters_json, note) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
    s.bind(1, version.integer(0))
        .bind(2, *measurement)
        .bind(3, fit.method)
        .bind(4, fit.residual_rms)
        .bind(5, nlohmann::json(fit.residuals).dump())
        .bind(6, nlohmann::json(fit.parameters).dump())
        .bind(7, fit.note)
        .run();
    const std::int64_t id = c.lastInsertId();
    transaction.commit();
    return id;
}

std::vector<Fit> fitsOfMeasurement(Database& db, std::string_view measurement_name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, std::string(kFitColumns) + "WHERE m.name = ?1 ORDER BY f.id");
    s.bind(1, measurement_name);
    auto out = readFits(c, s);
    transaction.commit();
    return out;
}

std::vector<Fit> fitsOfRecipe(Database& db, std::string_view recipe_name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, std::string(kFitColumns) + "WHERE r.name = ?1 ORDER BY f.id");
    s.bind(1, recipe_name);
    auto out = readFits(c, s);
    transaction.commit();
    return out;
}

}  // namespace paintlab::db
