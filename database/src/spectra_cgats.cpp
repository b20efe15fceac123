// CGATS.17 / IT8.7 spectra (spectra_files.h). Reading goes through the
// engine's CGATS reader (io/cgats.h, liblcms2's cmsIT8 parser, which accepts
// the keywords and data-format names of any instrument); here the table is
// read as spectra. Writing is plain text: one table with the keywords
// PaintLab reads back.

#include "paintlab/database/spectra_files.h"

#include "spectra_common.h"
#include "spectrum_checks.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/cgats.h"
#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <type_traits>

namespace paintlab::db {

namespace {

using io::formatNumber;

std::string upper(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

}  // namespace

std::optional<double> cgatsSpectralWavelength(std::string_view column) {
    const std::string name = upper(column);
    for (const std::string_view prefix :
         {"SPECTRAL_NM_", "SPECTRAL_NM", "SPECTRAL_", "SPEC_", "NM_", "NM", "R_", "R"})
        if (name.starts_with(prefix)) {
            const auto value = io::parseFiniteNumber(std::string_view(name).substr(prefix.size()));
            if (value && *value > 0.0) return value;
            return std::nullopt;
        }
    return std::nullopt;
}

std::vector<NamedSpectrum> parseSpectraCgats(std::string_view text, const std::string& source,
                                             const CgatsOptions& options) {
    const io::CgatsTable table = io::parseCgats(text, source);
    const auto& names = table.columns;
    const int columns = static_cast<int>(names.size());
    std::vector<std::pair<int, double>> spectral;  // column, wavelength
    std::optional<int> name_column;
    std::optional<int> id_column;
    for (int c = 0; c < columns; ++c) {
        const std::string& column = names[static_cast<std::size_t>(c)];
        if (upper(column) == "SAMPLE_NAME") name_column = c;
        if (upper(column) == "SAMPLE_ID") id_column = c;
        if (const auto wavelength = cgatsSpectralWavelength(column)) spectral.emplace_back(c, *wavelength);
    }
    if (spectral.empty())
        throw InputError(source, "DATA_FORMAT",
                         "no spectral column (SPECTRAL_NM380, SPECTRAL_380, NM380, SPEC_380, ...)");
    std::sort(spectral.begin(), spectral.end(),
              [](const auto& a, const auto& b) { return a.second < b.second; });
    for (std::size_t i = 1; i < spectral.size(); ++i)
        if (spectral[i].second == spectral[i - 1].second)
            throw InputError(source, "DATA_FORMAT." + names[static_cast<std::size_t>(spectral[i].first)],
                             "a second column for the same wavelength");

    if (table.rows.empty()) throw InputError(source, "NUMBER_OF_SETS", "the file holds no data set");
    const int rows = static_cast<int>(table.rows.size());

    std::string quantity = table.property("PAINTLAB_QUANTITY");
    if (quantity.empty()) quantity = options.quantity;
    std::string unit = options.unit.empty() ? table.property("PAINTLAB_UNIT") : options.unit;
    const bool unit_given = !unit.empty();
    if (!unit_given) unit = "1";
    std::string spectrum_source = options.source;
    if (spectrum_source.empty()) spectrum_source = table.property("PAINTLAB_SOURCE");
    if (spectrum_source.empty()) {
        spectrum_source = "CGATS file " + std::filesystem::path(source).filename().string();
        for (const char* key : {"INSTRUMENTATION", "ORIGINATOR", "DESCRIPTOR"})
            if (const std::string value = table.property(key); !value.empty())
                spectrum_source.append(", ").append(key).append(" ").append(value);
    }
    const std::string date = table.property("CREATED");
    const std::string stem = std::filesystem::path(source).stem().string();

    std::vector<NamedSpectrum> out;
    std::vector<std::string> labels;
    double largest = 0.0;
    std::string largest_at;
    for (int row = 0; row < rows; ++row) {
        std::string label = "data set " + std::to_string(row + 1);
        NamedSpectrum s;
        const auto cell = [&](int column) -> const std::string& {
            return table.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(column)];
        };
        if (name_column) s.name = cell(*name_column);
        if (s.name.empty() && id_column) s.name = cell(*id_column);
        if (s.name.empty()) s.name = stem + " " + std::to_string(row + 1);
        label += " '" + s.name + "'";
        std::vector<double> wavelengths;
        std::vector<double> values;
        for (const auto& [column, wavelength] : spectral) {
            const std::string& text_value = cell(column);
            const auto value = io::parseFiniteNumber(text_value);
            if (!value)
                throw InputError(source, label + "." + names[static_cast<std::size_t>(column)],
                                 text_value.empty() ? std::string("missing (truncated file?)")
                                                    : "'" + text_value + "' is not a finite number");
            if (*value > largest) {
                largest = *value;
                largest_at = label + "." + names[static_cast<std::size_t>(column)];
            }
            wavelengths.push_back(wavelength);
            values.push_back(*value);
        }
        s.quantity = quantity;
        s.info = {unit, spectrum_source, date};
        s.spectrum = detail::checkedSpectrum(source, label, std::move(wavelengths), std::move(values));
        out.push_back(std::move(s));
        labels.push_back(label);
    }
    if (!unit_given && largest > 2.0)
        throw InputError(source, largest_at,
                         "value " + formatNumber(largest) +
                             " is above 2: is this reflectance in percent? Give the unit (% or 1) explicitly "
                             "(paintlab-cli: --unit)");
    detail::finishNamedSpectra(out, labels, source);
    return out;
}

std::string spectraToCgats(const std::vector<NamedSpectrum>& spectra) {
    if (spectra.empty()) throw InputError("<cgats>", "", "no spectrum to write");
    const NamedSpectrum& first = spectra.front();
    for (const auto& s : spectra) {
        const std::string field = "spectrum '" + s.name + "'";
        if (s.spectrum.wavelengthsNm() != first.spectrum.wavelengthsNm() || s.spectrum.isConstant())
            throw InputError("<cgats>", field,
                             "not on the wavelength grid of '" + first.name +
                                 "': one CGATS table needs one grid (export as CSV or JSON instead)");
        if (s.quantity != first.quantity || s.info.unit != first.info.unit)
            throw InputError("<cgats>", field,
                             "quantity or unit differs from '" + first.name +
                                 "': one CGATS table holds one quantity (export as CSV or JSON instead)");
        for (const std::string* text : {&s.name, &s.quantity, &s.info.unit, &s.info.source, &s.info.date})
            if (text->find_first_of("\"\r\n") != std::string::npos)
                throw InputError("<cgats>", field,
                                 "a double quote or line break cannot be written in a CGATS string "
                                 "(export as CSV or JSON instead)");
    }
    const auto quoted = [](const std::string& text) { return "\"" + text + "\""; };
    const auto number = [](double value) { return formatNumber(value, io::NumberFormat::Shortest); };
    std::string out = "CGATS.17\n";
    out += "ORIGINATOR " + quoted("PaintLab") + "\n";
    out += "DESCRIPTOR " + quoted(first.quantity + " spectra") + "\n";
    const bool one_source = std::all_of(spectra.begin(), spectra.end(),
                                        [&](const auto& s) { return s.info.source == first.info.source; });
    const bool one_date = std::all_of(spectra.begin(), spectra.end(),
                                      [&](const auto& s) { return s.info.date == first.info.date; });
    if (one_date && !first.info.date.empty()) out += "CREATED " + quoted(first.info.date) + "\n";
    if (one_source && !first.info.source.empty())
        out += "KEYWORD \"PAINTLAB_SOURCE\"\nPAINTLAB_SOURCE " + quoted(first.info.source) + "\n";
    out += "KEYWORD \"PAINTLAB_QUANTITY\"\nPAINTLAB_QUANTITY " + quoted(first.quantity) + "\n";
    out += "KEYWORD \"PAINTLAB_UNIT\"\nPAINTLAB_UNIT " + quoted(first.info.unit) + "\n";
    const auto& wavelengths = first.spectrum.wavelengthsNm();
    out += "NUMBER_OF_FIELDS " + std::to_string(wavelengths.size() + 2) +
           "\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_NAME";
    for (const double wavelength : wavelengths) out += " SPECTRAL_NM" + number(wavelength);
    out += "\nEND_DATA_FORMAT\nNUMBER_OF_SETS " + std::to_string(spectra.size()) + "\nBEGIN_DATA\n";
    for (std::size_t i = 0; i < spectra.size(); ++i) {
        out.append(std::to_string(i + 1)).append(" ").append(quoted(spectra[i].name));
        for (const double value : spectra[i].spectrum.values()) out.append(" ").append(number(value));
        out += "\n";
    }
    out += "END_DATA\n";
    return out;
}

}  // namespace paintlab::db
