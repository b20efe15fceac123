// Measurement files: JSON and CSV (measurement_files.h), and the JSON of
// the measurement table's data column (measurement_json.h).

#include "paintlab/database/measurement_files.h"

#include "measurement_json.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"

#include "json_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace paintlab::db {

namespace detail {

namespace {

using Json = nlohmann::json;

using Fields = jsonio::ObjectReader;

}  // namespace

nlohmann::ordered_json measurementJson(const Measurement& m, bool with_description) {
    nlohmann::ordered_json out;
    if (with_description) {
        out["format"] = "paintlab-measurement";
        out["format_version"] = 1;
        out["name"] = m.name;
        out["kind"] = measurementKindName(m.kind);
        out["instrument"] = m.instrument;
        out["geometry"] = m.geometry;
        out["sample"] = m.sample;
        out["measured_at"] = m.measured_at;
        out["source"] = m.source;
    }
    if (m.kind == MeasurementKind::MultiAngle) {
        out["illuminant"] = m.illuminant;
        out["observer"] = m.observer;
        out["readings"] = nlohmann::ordered_json::array();
        if (!m.wavelengths_nm.empty()) out["wavelengths_nm"] = m.wavelengths_nm;
        for (const auto& r : m.readings) {
            nlohmann::ordered_json reading{{"illumination_deg", r.illumination_deg},
                                           {"aspecular_deg", r.aspecular_deg},
                                           {"L", r.L},
                                           {"a", r.a},
                                           {"b", r.b}};
            // Only out of the plane: in-plane readings are written as before azimuths.
            if (!isInPlane(r.azimuth_deg)) reading["azimuth_deg"] = r.azimuth_deg;
            if (!r.reflectance.empty()) reading["reflectance"] = r.reflectance;
            out["readings"].push_back(std::move(reading));
        }
    } else {
        if (!m.channels.empty()) out["channels"] = m.channels;
        if (!m.wavelengths_nm.empty()) out["wavelengths_nm"] = m.wavelengths_nm;
        out["samples"] = nlohmann::ordered_json::array();
        for (const auto& s : m.samples)
            out["samples"].push_back({{"theta_i_deg", s.theta_i_deg},
                                      {"phi_i_deg", s.phi_i_deg},
                                      {"theta_o_deg", s.theta_o_deg},
                                      {"phi_o_deg", s.phi_o_deg},
                                      {"values", s.values}});
    }
    return out;
}

void readMeasurementJson(const nlohmann::json& json, bool with_description, Measurement& m,
                         const std::string& source) {
    Fields f(json, "", source);
    if (with_description) {
        if (f.string("format", true) != "paintlab-measurement")
            f.fail("format", "expected \"paintlab-measurement\"");
        if (f.number("format_version", "a number") != 1.0)
            f.fail("format_version", "only version 1 is known to this build");
        m.name = f.string("name", true);
        const std::string kind = f.string("kind", true);
        const auto parsed = parseMeasurementKind(kind);
        if (!parsed) f.fail("kind", "unknown kind '" + kind + "' (multiangle or brdf)");
        m.kind = *parsed;
        m.instrument = f.string("instrument", false);
        m.geometry = f.string("geometry", false);
        m.sample = f.string("sample", false);
        m.measured_at = f.string("measured_at", false);
        m.source = f.string("source", false);
    }
    if (m.kind == MeasurementKind::MultiAngle) {
        if (f.has("illuminant")) m.illuminant = f.string("illuminant", true);
        if (f.has("observer")) m.observer = f.string("observer", true);
        if (f.has("wavelengths_nm")) m.wavelengths_nm = f.numbers("wavelengths_nm");
        const Json& readings = f.require("readings", "the readings");
        if (!readings.is_array()) f.fail("readings", "expected an array");
        bool lab_from_spectra = false;
        for (std::size_t i = 0; i < readings.size(); ++i) {
            Fields r(readings[i], f.elementPath("readings", i), source);
            MultiAngleReading reading;
            if (r.has("illumination_deg"))
                reading.illumination_deg = r.number("illumination_deg", "a number");
            reading.aspecular_deg = r.number("aspecular_deg", "a number");
            if (r.has("azimuth_deg")) reading.azimuth_deg = r.number("azimuth_deg", "a number");
            if (r.has("reflectance")) reading.reflectance = r.numbers("reflectance");
            // A spectral reading may leave CIELAB out: it follows from the spectrum.
            if (reading.reflectance.empty() || r.has("L") || r.has("a") || r.has("b")) {
                reading.L = r.number("L", "a number");
                reading.a = r.number("a", "a number");
                reading.b = r.number("b", "a number");
            } else {
                lab_from_spectra = true;
            }
            r.finish();
            m.readings.push_back(std::move(reading));
        }
        if (lab_from_spectra) labFromSpectra(m, source);
    } else {
        if (f.has("channels")) {
            const Json& channels = f.require("channels", "channel names");
            if (!channels.is_array()) f.fail("channels", "expected an array of strings");
            for (const auto& c : channels) {
                if (!c.is_string()) f.fail("channels", "expected an array of strings");
                m.channels.push_back(c.get<std::string>());
            }
        }
        if (f.has("wavelengths_nm")) m.wavelengths_nm = f.numbers("wavelengths_nm");
        const Json& samples = f.require("samples", "the samples");
        if (!samples.is_array()) f.fail("samples", "expected an array");
        for (std::size_t i = 0; i < samples.size(); ++i) {
            Fields s(samples[i], f.elementPath("samples", i), source);
            BrdfSample sample{s.number("theta_i_deg", "a number"), s.number("phi_i_deg", "a number"),
                              s.number("theta_o_deg", "a number"), s.number("phi_o_deg", "a number"),
                              s.numbers("values")};
            s.finish();
            m.samples.push_back(std::move(sample));
        }
    }
    f.finish();
}

}  // namespace detail

namespace {

using io::CsvRecord;
using io::CsvTable;

std::optional<double> wavelengthColumn(const std::string& column) {
    std::string_view text = column;
    if (text.ends_with("nm")) text.remove_suffix(2);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

std::string firstColumn(const CsvTable& table, std::initializer_list<std::string_view> names) {
    for (const auto name : names)
        if (table.column(name)) return std::string(name);
    return {};
}

}  // namespace

Measurement parseMeasurementJson(std::string_view text, const std::string& source) {
    const nlohmann::json document = jsonio::parseUntrustedJson(text, source);
    Measurement m;
    detail::readMeasurementJson(document, true, m, source);
    validateMeasurement(m, source);
    return m;
}

Measurement parseMeasurementCsv(std::string_view text, const std::string& source,
                                const Measurement& description) {
    const CsvTable table = CsvTable::parse(text, source);
    Measurement m = description;
    m.readings.clear();
    m.samples.clear();
    m.channels.clear();
    m.wavelengths_nm.clear();
    if (table.column("theta_i_deg")) {
        m.kind = MeasurementKind::Brdf;
        table.requireColumns({"theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg"});
        std::vector<std::string> value_columns;
        for (const auto& column : table.header()) {
            if (column == "theta_i_deg" || column == "phi_i_deg" || column == "theta_o_deg" ||
                column == "phi_o_deg")
                continue;
            if (column == "R" || column == "G" || column == "B") {
                m.channels.push_back(column);
            } else if (const auto wavelength = wavelengthColumn(column)) {
                m.wavelengths_nm.push_back(*wavelength);
            } else {
                throw InputError(source, "line 1",
                                 "unknown column '" + column +
                                     "' (R, G, B or a wavelength in nm such as 380 or 380nm)");
            }
            value_columns.push_back(column);
        }
        if (value_columns.empty())
            throw InputError(source, "line 1", "no value column (R, G, B or one column per wavelength)");
        for (const auto& record : table.records()) {
            BrdfSample sample{table.requiredNumber(record, "theta_i_deg"),
                              table.requiredNumber(record, "phi_i_deg"),
                              table.requiredNumber(record, "theta_o_deg"),
                              table.requiredNumber(record, "phi_o_deg"),
                              {}};
            for (const auto& column : value_columns)
                sample.values.push_back(table.requiredNumber(record, column));
            m.samples.push_back(std::move(sample));
        }
    } else {
        m.kind = MeasurementKind::MultiAngle;
        const std::string l = firstColumn(table, {"L", "L*"});
        const std::string a = firstColumn(table, {"a", "a*"});
        const std::string b = firstColumn(table, {"b", "b*"});
        const bool by_geometry = table.column("geometry").has_value();
        if (!by_geometry) table.requireColumns({"aspecular_deg"});
        std::vector<std::string> spectrum_columns;
        for (const auto& column : table.header())
            if (const auto wavelength = wavelengthColumn(column)) {
                m.wavelengths_nm.push_back(*wavelength);
                spectrum_columns.push_back(column);
            }
        // Spectral readings may leave CIELAB out (it follows from the spectrum).
        const bool lab_from_spectra = !spectrum_columns.empty() && l.empty() && a.empty() && b.empty();
        if (!lab_from_spectra) {
            if (l.empty()) table.requireColumns({"L"});
            if (a.empty()) table.requireColumns({"a"});
            if (b.empty()) table.requireColumns({"b"});
        }
        std::vector<std::string_view> allowed{
            "geometry", "aspecular_deg", "illumination_deg", "azimuth_deg", "L", "a", "b", "L*", "a*", "b*"};
        allowed.insert(allowed.end(), spectrum_columns.begin(), spectrum_columns.end());
        table.allowOnlyColumns(allowed);
        for (const auto& record : table.records()) {
            MultiAngleReading reading;
            if (by_geometry && !table.field(record, "geometry").empty()) {
                const std::string& name = table.field(record, "geometry");
                const auto geometry = parseMultiAngleGeometry(name);
                if (!geometry)
                    throw InputError(source, CsvTable::where(record, "geometry"),
                                     "'" + name + "' is not a geometry like 45as15 or 45as-15");
                reading.illumination_deg = geometry->illumination_deg;
                reading.aspecular_deg = geometry->aspecular_deg;
                reading.azimuth_deg = geometry->azimuth_deg;
                // An angle column beside the name must say the same (an azimuth_deg of 90
                // beside "45as25" was ignored, the reading stored in the plane).
                const auto agrees = [&](std::string_view column, double from_name) {
                    if (const auto value = table.number(record, column); value && *value != from_name)
                        throw InputError(source, CsvTable::where(record, column),
                                         io::formatNumber(*value) + " disagrees with the geometry '" + name +
                                             "' (" + io::formatNumber(from_name) + ")");
                };
                agrees("illumination_deg", reading.illumination_deg);
                agrees("aspecular_deg", reading.aspecular_deg);
                agrees("azimuth_deg", reading.azimuth_deg);
            } else {
                reading.aspecular_deg = table.requiredNumber(record, "aspecular_deg");
                reading.illumination_deg = table.number(record, "illumination_deg").value_or(45.0);
                reading.azimuth_deg = table.number(record, "azimuth_deg").value_or(0.0);
            }
            if (!lab_from_spectra) {
                reading.L = table.requiredNumber(record, l);
                reading.a = table.requiredNumber(record, a);
                reading.b = table.requiredNumber(record, b);
            }
            for (const auto& column : spectrum_columns)
                reading.reflectance.push_back(table.requiredNumber(record, column));
            m.readings.push_back(std::move(reading));
        }
        if (lab_from_spectra) labFromSpectra(m, source);
    }
    validateMeasurement(m, source);
    return m;
}

std::string measurementToJson(const Measurement& measurement) {
    return detail::measurementJson(measurement, true).dump(2) + "\n";
}

std::string measurementToCsv(const Measurement& m) {
    std::string out;
    if (m.kind == MeasurementKind::MultiAngle) {
        // azimuth_deg only when a reading is out of the plane: in-plane files are as before azimuths.
        const bool azimuths =
            std::any_of(m.readings.begin(), m.readings.end(),
                        [](const MultiAngleReading& r) { return !isInPlane(r.azimuth_deg); });
        std::vector<std::string> header{"illumination_deg", "aspecular_deg", "L", "a", "b"};
        if (azimuths) header.insert(header.begin() + 2, "azimuth_deg");
        for (const double w : m.wavelengths_nm) header.push_back(io::csvNumber(w) + "nm");
        out = io::csvLine(header);
        for (const auto& r : m.readings) {
            std::vector<std::string> fields{io::csvNumber(r.illumination_deg), io::csvNumber(r.aspecular_deg),
                                            io::csvNumber(r.L), io::csvNumber(r.a), io::csvNumber(r.b)};
            if (azimuths) fields.insert(fields.begin() + 2, io::csvNumber(r.azimuth_deg));
            for (const double v : r.reflectance) fields.push_back(io::csvNumber(v));
            out += io::csvLine(fields);
        }
        return out;
    }
    std::vector<std::string> header{"theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg"};
    for (const auto& c : m.channels) header.push_back(c);
    for (const double w : m.wavelengths_nm) header.push_back(io::csvNumber(w) + "nm");
    out = io::csvLine(header);
    for (const auto& s : m.samples) {
        std::vector<std::string> fields{io::csvNumber(s.theta_i_deg), io::csvNumber(s.phi_i_deg),
                                        io::csvNumber(s.theta_o_deg), io::csvNumber(s.phi_o_deg)};
        for (const double v : s.values) fields.push_back(io::csvNumber(v));
        out += io::csvLine(fields);
    }
    return out;
}

}  // namespace paintlab::db
