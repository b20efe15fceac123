// Multi-angle CGATS exports (multiangle_cgats.h). The text goes through the
// one CGATS reader (io/cgats.h, liblcms2); here the table is read as the
// geometries of one panel.

#include "multiangle_cgats.h"

#include "paintlab/database/measurements.h"
#include "paintlab/database/spectra_files.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/io/cgats.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"

#include "json_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace paintlab::plugins::multiangle {

namespace {

using io::formatNumber;

constexpr std::array<std::string_view, 4> kGeometryFields{"GEOMETRY", "MEASUREMENT_GEOMETRY", "MEAS_GEOMETRY",
                                                          "ANGLE"};

std::string upper(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())) != 0)
        text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())) != 0) text.remove_suffix(1);
    return text;
}

// The geometry at the end of a sample name ("blue pearl 45as15"): the name
// without it and the geometry.
std::optional<std::pair<std::string, db::MultiAngleGeometry>> geometrySuffix(std::string_view name) {
    name = trimmed(name);
    const auto space = name.find_last_of(" \t");
    const std::string_view last = space == std::string_view::npos ? name : name.substr(space + 1);
    const auto geometry = db::parseMultiAngleGeometry(last);
    if (!geometry) return std::nullopt;
    return std::pair{std::string(trimmed(name.substr(0, name.size() - last.size()))), *geometry};
}

struct Columns {
    std::optional<std::size_t> geometry;
    std::optional<std::size_t> illumination;
    std::optional<std::size_t> aspecular;
    std::optional<std::size_t> name;
    std::array<std::optional<std::size_t>, 3> lab;
    std::vector<std::pair<std::size_t, double>> spectral;  // column, wavelength (ascending)
};

Columns findColumns(const io::CgatsTable& table, const std::string& source) {
    Columns c;
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
        const std::string name = upper(table.columns[i]);
        if (std::find(kGeometryFields.begin(), kGeometryFields.end(), name) != kGeometryFields.end()) {
            if (!c.geometry) c.geometry = i;
        } else if (name == "ILLUMINATION_ANGLE") {
            c.illumination = i;
        } else if (name == "ASPECULAR_ANGLE") {
            c.aspecular = i;
        } else if (name == "SAMPLE_NAME") {
            c.name = i;
        } else if (name == "LAB_L" || name == "LAB_A" || name == "LAB_B") {
            c.lab[name == "LAB_L" ? 0 : name == "LAB_A" ? 1 : 2] = i;
        } else if (const auto wavelength = db::cgatsSpectralWavelength(name)) {
            c.spectral.emplace_back(i, *wavelength);
        }
    }
    std::sort(c.spectral.begin(), c.spectral.end(),
              [](const auto& a, const auto& b) { return a.second < b.second; });
    for (std::size_t i = 1; i < c.spectral.size(); ++i)
        if (c.spectral[i].second == c.spectral[i - 1].second)
            throw InputError(source, "DATA_FORMAT." + table.columns[c.spectral[i].first],
                             "a second field for the same wavelength");
    const int lab_fields = static_cast<int>(
        std::count_if(c.lab.begin(), c.lab.end(), [](const auto& f) { return f.has_value(); }));
    if (lab_fields != 0 && lab_fields != 3)
        throw InputError(source, "DATA_FORMAT", "has some of LAB_L, LAB_A, LAB_B but not all three");
    if (lab_fields == 0 && c.spectral.empty())
        throw InputError(
            source, "DATA_FORMAT",
            "neither LAB_L, LAB_A, LAB_B nor spectral fields (SPECTRAL_NM400, SPECTRAL_400, ...)");
    if (c.spectral.size() == 1)
        throw InputError(source, "DATA_FORMAT." + table.columns[c.spectral.front().first],
                         "the only spectral field: a spectrum needs at least two wavelengths");
    if (c.illumination.has_value() != c.aspecular.has_value())
        throw InputError(source, "DATA_FORMAT", "ILLUMINATION_ANGLE and ASPECULAR_ANGLE go together");
    return c;
}

// One data set of the file.
struct Row {
    std::string label;  // "data set 3 (45as15)"
    std::string sample;
    db::MultiAngleGeometry geometry;
    std::optional<Lab> lab;
    std::vector<double> values;  // spectral values as written (unit not applied)
};

std::vector<Row> readRows(const io::CgatsTable& table, const Columns& c, const std::string& source) {
    std::vector<Row> rows;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const auto& cells = table.rows[r];
        Row row;
        row.label = "data set " + std::to_string(r + 1);
        const auto field = [&](std::size_t column) { return row.label + "." + table.columns[column]; };
        const auto number = [&](std::size_t column) {
            const std::string& text = cells[column];
            const auto value = io::parseFiniteNumber(text);
            if (!value)
                throw InputError(source, field(column),
                                 text.empty() ? std::string("missing (truncated file?)")
                                              : "'" + text + "' is not a finite number");
            return *value;
        };
        if (c.name) row.sample = std::string(trimmed(cells[*c.name]));
        if (c.geometry) {
            const std::string& text = cells[*c.geometry];
            const auto geometry = db::parseMultiAngleGeometry(text);
            if (!geometry)
                throw InputError(source, field(*c.geometry),
                                 text.empty()
                                     ? std::string("missing (truncated file?)")
                                     : "'" + text + "' is not a geometry like 45as15, 45as-15 or 15as80");
            row.geometry = *geometry;
        } else if (c.illumination) {
            row.geometry.illumination_deg = number(*c.illumination);
            row.geometry.aspecular_deg = number(*c.aspecular);
            // A name ending in an out-of-plane geometry has an azimuth these fields
            // cannot hold: refused rather than read in the plane.
            if (const auto suffix = c.name ? geometrySuffix(row.sample) : std::nullopt;
                suffix && !isInPlane(suffix->second.azimuth_deg))
                throw InputError(source, field(*c.name),
                                 "'" + row.sample +
                                     "' names an azimuth that ILLUMINATION_ANGLE and ASPECULAR_ANGLE cannot "
                                     "hold: give a GEOMETRY field (45as25az90)");
        } else {
            const auto suffix = c.name ? geometrySuffix(row.sample) : std::nullopt;
            if (!suffix)
                throw InputError(
                    source, c.name ? field(*c.name) : std::string("DATA_FORMAT"),
                    "no geometry: give a GEOMETRY field (45as15, 45as-15, ...), ILLUMINATION_ANGLE "
                    "and ASPECULAR_ANGLE, or end SAMPLE_NAME in the geometry");
            row.sample = suffix->first;
            row.geometry = suffix->second;
        }
        const db::MultiAngleGeometry& g = row.geometry;
        row.label +=
            " (" + db::multiAngleGeometryName(g.illumination_deg, g.aspecular_deg, g.azimuth_deg) + ")";
        const std::string geometry_field = row.label + ".geometry";
        if (!(g.illumination_deg >= 0.0 && g.illumination_deg < 90.0))
            throw InputError(source, geometry_field,
                             "illumination " + formatNumber(g.illumination_deg) +
                                 "° is not between 0 and 90");
        if (!(std::abs(g.azimuth_deg) <= 180.0))
            throw InputError(source, geometry_field,
                             "azimuth " + formatNumber(g.azimuth_deg) + "° is not between -180 and 180");
        if (!isInPlane(g.azimuth_deg))
            if (const std::string problem = outOfPlaneFormProblem(g.aspecular_deg, g.azimuth_deg);
                !problem.empty())
                throw InputError(source, geometry_field, problem);
        // Out of the plane too: the detector turned about the specular direction (engine/multiangle.h).
        if (!(detectorPolarAngleDeg(multiAngleDirections(g.illumination_deg, g.aspecular_deg,
                                                         g.azimuth_deg)) <= kMaxDetectorPolarDeg))
            throw InputError(
                source, geometry_field,
                "aspecular " + formatNumber(g.aspecular_deg) + "°" +
                    (isInPlane(g.azimuth_deg) ? "" : " at azimuth " + formatNumber(g.azimuth_deg) + "°") +
                    " puts the detector below the horizon");
        if (c.lab[0]) row.lab = Lab{number(*c.lab[0]), number(*c.lab[1]), number(*c.lab[2])};
        if (row.lab && !(row.lab->L >= 0.0 && row.lab->L <= 400.0))
            throw InputError(source, field(*c.lab[0]), formatNumber(row.lab->L) + " is outside 0 to 400");
        for (const auto& [column, wavelength] : c.spectral) {
            const double value = number(column);
            if (value < 0.0)
                throw InputError(source, field(column), "a reflectance factor cannot be negative");
            row.values.push_back(value);
        }
        rows.push_back(std::move(row));
    }
    return rows;
}

// The rows of the one sample the measurement is of (multiangle_cgats.h).
std::vector<Row> oneSample(std::vector<Row> rows, const std::string& wanted, const std::string& source) {
    std::vector<std::string> samples;
    for (const auto& row : rows)
        if (std::find(samples.begin(), samples.end(), row.sample) == samples.end())
            samples.push_back(row.sample);
    if (samples.size() > 1) {
        if (std::find(samples.begin(), samples.end(), wanted) == samples.end()) {
            std::string list;
            for (std::size_t i = 0; i < samples.size() && i < 10; ++i)
                list += (i > 0 ? ", '" : "'") + samples[i] + "'";
            if (samples.size() > 10) list += ", ...";
            throw InputError(source, "SAMPLE_NAME",
                             "the file holds " + std::to_string(samples.size()) + " samples (" + list +
                                 "); name the one to read (paintlab-cli: --sample NAME)");
        }
        std::erase_if(rows, [&](const Row& row) { return row.sample != wanted; });
    }
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (rows[i].geometry.illumination_deg == rows[j].geometry.illumination_deg &&
                rows[i].geometry.aspecular_deg == rows[j].geometry.aspecular_deg &&
                rows[i].geometry.azimuth_deg == rows[j].geometry.azimuth_deg)
                throw InputError(source, rows[i].label,
                                 "the same geometry as " + rows[j].label +
                                     (rows[i].sample.empty() ? "" : " of sample '" + rows[i].sample + "'"));
    return rows;
}

// "Illumination=D50  ObserverAngle=2°" (MEASUREMENT_SOURCE, as i1Profiler writes it): the value of a key.
std::string measurementSourceValue(const std::string& text, std::string_view key) {
    const std::string haystack = upper(text);
    const auto at = haystack.find(upper(key) + "=");
    if (at == std::string::npos) return {};
    const auto start = at + key.size() + 1;
    const auto end = text.find_first_of(" \t;,", start);
    return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// The keyword's value, else the MEASUREMENT_SOURCE entry; with the field it came from.
std::pair<std::string, std::string> condition(const io::CgatsTable& table, const std::string& keyword,
                                              std::string_view entry) {
    if (std::string value = table.property(keyword); !value.empty()) return {value, keyword};
    return {measurementSourceValue(table.property("MEASUREMENT_SOURCE"), entry), "MEASUREMENT_SOURCE"};
}

void readConditions(const io::CgatsTable& table, db::Measurement& m, const std::string& source) {
    const auto [illuminant, illuminant_field] = condition(table, "ILLUMINANT", "Illumination");
    if (!illuminant.empty()) {
        const std::string name = upper(trimmed(illuminant));
        if (name != "D65" && name != "D50" && name != "A")
            throw InputError(source, illuminant_field,
                             "illuminant '" + illuminant +
                                 "' is not D65, D50 or A (what PaintLab computes CIELAB for)");
        m.illuminant = name;
    }
    const auto [observer, observer_field] = condition(table, "OBSERVER", "ObserverAngle");
    if (!observer.empty()) {
        std::string digits;
        for (const char ch : observer)
            if (std::isdigit(static_cast<unsigned char>(ch)) != 0) digits.push_back(ch);
        if (digits != "2" && digits != "10")
            throw InputError(source, observer_field, "observer '" + observer + "' is not 2° or 10°");
        m.observer = digits + "deg";
    }
}

double labDistance(const Lab& x, const Lab& y) { return std::hypot(x.L - y.L, x.a - y.a, x.b - y.b); }

// What the file's spectral values are divided by to give reflectance factors: 100 or 1 (multiangle_cgats.h).
double spectralScale(const io::CgatsTable& table, const std::vector<Row>& rows, const db::Measurement& m,
                     const ReadOptions& options, const std::string& source) {
    std::string unit = options.cgats.unit;
    std::string field = "unit";
    if (unit.empty() && !table.property("PAINTLAB_UNIT").empty()) {
        unit = table.property("PAINTLAB_UNIT");
        field = "PAINTLAB_UNIT";
    }
    if (!unit.empty()) {
        if (unit == "%") return 100.0;
        if (unit == "1") return 1.0;
        throw InputError(source, field, "unit '" + unit + "' is neither % nor 1");
    }
    // With CIELAB in the file: the scale that reproduces it.
    const ColourConditions conditions{db::measurementIlluminant(m), db::measurementObserver(m)};
    double distance_fraction = 0.0;
    double distance_percent = 0.0;
    bool compared = false;
    for (const auto& row : rows) {
        if (!row.lab) continue;
        std::vector<double> percent = row.values;
        for (double& v : percent) v /= 100.0;
        distance_fraction +=
            labDistance(spectrumColour(m.wavelengths_nm, row.values, conditions).lab, *row.lab);
        distance_percent += labDistance(spectrumColour(m.wavelengths_nm, percent, conditions).lab, *row.lab);
        compared = true;
    }
    if (compared) return distance_percent < distance_fraction ? 100.0 : 1.0;
    // Far from the specular direction a paint's reflectance factor stays well below 2.
    for (const auto& row : rows)
        if (std::abs(row.geometry.aspecular_deg) >= 45.0 &&
            *std::max_element(row.values.begin(), row.values.end()) > 2.0)
            return 100.0;
    throw InputError(
        source, field,
        "cannot tell whether the spectra are in percent or fractions (no LAB_L, LAB_A, LAB_B to check "
        "them against): give the unit (paintlab-cli: --unit % or --unit 1)");
}

// "45as-15,15,25,25az90; 15as-45,...": per illumination, the aspecular
// angles (with the azimuth out of the plane) in the file's order.
std::string geometryDescription(const std::vector<db::MultiAngleReading>& readings) {
    std::map<double, std::vector<std::string>, std::greater<>> by_illumination;
    for (const auto& r : readings) {
        const std::string name =
            db::multiAngleGeometryName(r.illumination_deg, r.aspecular_deg, r.azimuth_deg);
        by_illumination[r.illumination_deg].push_back(name.substr(name.find("as") + 2));
    }
    std::string out;
    for (const auto& [illumination, aspeculars] : by_illumination) {
        if (!out.empty()) out += "; ";
        out += formatNumber(illumination, io::NumberFormat::Shortest) + "as";
        for (std::size_t i = 0; i < aspeculars.size(); ++i) {
            if (i > 0) out.push_back(',');
            out.append(aspeculars[i]);
        }
    }
    return out;
}

}  // namespace

double probe(std::string_view head) {
    const auto format = head.find("BEGIN_DATA_FORMAT");
    if (format == std::string_view::npos) return 0.0;
    const auto format_end = head.find("END_DATA_FORMAT", format + 17);
    const std::string fields =
        upper(head.substr(format + 17, format_end == std::string_view::npos ? std::string_view::npos
                                                                            : format_end - format - 17));
    std::vector<std::string> names;
    std::size_t start = 0;
    while (start < fields.size()) {
        const auto end = std::min(fields.find_first_of(" \t\r\n", start), fields.size());
        if (end > start) names.push_back(fields.substr(start, end - start));
        start = end + 1;
    }
    const auto has = [&](std::string_view name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    for (const auto name : kGeometryFields)
        if (has(name)) return 0.95;
    if (has("ILLUMINATION_ANGLE") && has("ASPECULAR_ANGLE")) return 0.95;
    // Geometry names in the data ("blue pearl 45as15").
    const auto data = head.find("BEGIN_DATA", format_end == std::string_view::npos ? format : format_end);
    if (data != std::string_view::npos) {
        std::string_view rest = head.substr(data + 10);
        while (!rest.empty()) {
            const auto end = std::min(rest.find_first_of(" \t\r\n\""), rest.size());
            const std::string_view token = rest.substr(0, end);
            if (token.find("as") != std::string_view::npos && db::parseMultiAngleGeometry(token)) return 0.9;
            rest.remove_prefix(std::min(end + 1, rest.size()));
        }
    }
    return 0.1;  // CGATS, but spectra of single samples as far as we can see
}

db::Measurement parse(std::string_view text, const std::string& source, const ReadOptions& options) {
    const io::CgatsTable table = io::parseCgats(text, source);
    const Columns columns = findColumns(table, source);
    if (table.rows.empty()) {
        const std::string sets = table.property("NUMBER_OF_SETS");
        throw InputError(source, "NUMBER_OF_SETS",
                         sets.empty() ? std::string("the file holds no data set")
                                      : "'" + sets + "' is not a number of data sets this file can hold");
    }
    std::vector<Row> rows = oneSample(readRows(table, columns, source), options.description.sample, source);

    db::Measurement m = options.description;
    m.kind = db::MeasurementKind::MultiAngle;
    m.readings.clear();
    m.samples.clear();
    m.channels.clear();
    m.wavelengths_nm.clear();
    if (m.name.empty()) m.name = std::filesystem::path(source).stem().string();
    if (m.instrument.empty()) m.instrument = table.property("INSTRUMENTATION");
    if (m.sample.empty()) m.sample = rows.front().sample;
    if (m.measured_at.empty()) m.measured_at = table.property("CREATED");
    if (m.source.empty()) {
        m.source = "CGATS file " + std::filesystem::path(source).filename().string();
        if (const std::string originator = table.property("ORIGINATOR"); !originator.empty())
            m.source += ", ORIGINATOR " + originator;
    }
    readConditions(table, m, source);
    for (const auto& [column, wavelength] : columns.spectral) m.wavelengths_nm.push_back(wavelength);
    const double divisor = m.wavelengths_nm.empty() ? 1.0 : spectralScale(table, rows, m, options, source);

    bool lab_missing = false;
    for (auto& row : rows) {
        db::MultiAngleReading r;
        r.illumination_deg = row.geometry.illumination_deg;
        r.aspecular_deg = row.geometry.aspecular_deg;
        r.azimuth_deg = row.geometry.azimuth_deg;
        for (const double value : row.values) r.reflectance.push_back(value / divisor);
        if (row.lab) {
            r.L = row.lab->L;
            r.a = row.lab->a;
            r.b = row.lab->b;
        }
        lab_missing = lab_missing || !row.lab;
        m.readings.push_back(std::move(r));
    }
    if (lab_missing) db::labFromSpectra(m, source);
    if (m.geometry.empty()) m.geometry = geometryDescription(m.readings);
    db::validateMeasurement(m, source);
    return m;
}

db::Measurement readFile(const std::filesystem::path& file, const ReadOptions& options) {
    ReadOptions named = options;
    if (named.description.name.empty()) named.description.name = file.stem().string();
    return parse(jsonio::readBoundedTextFile(file, kMaxFileBytes), file.string(), named);
}

}  // namespace paintlab::plugins::multiangle
