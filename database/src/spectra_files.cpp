// JSON and CSV files of named spectra (spectra_files.h); CGATS is in spectra_cgats.cpp.

#include "paintlab/database/spectra_files.h"

#include "spectra_common.h"
#include "spectrum_checks.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"

#include "json_reader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iterator>
#include <map>

namespace paintlab::db {

namespace {

using io::CsvRecord;
using io::CsvTable;
using Json = nlohmann::json;

using io::formatNumber;

}  // namespace

namespace detail {

void finishNamedSpectra(std::vector<NamedSpectrum>& spectra, const std::vector<std::string>& labels,
                        const std::string& source) {
    for (std::size_t i = 0; i < spectra.size(); ++i) {
        NamedSpectrum& s = spectra[i];
        if (s.name.empty())
            throw InputError(source, labels[i] + ".name", "empty; every spectrum needs a name");
        if (s.quantity.empty()) throw InputError(source, labels[i] + ".quantity", "empty");
        for (std::size_t j = 0; j < i; ++j)
            if (spectra[j].name == s.name)
                throw InputError(source, labels[i] + ".name",
                                 "'" + s.name + "' appears twice in the file (first at " + labels[j] + ")");
        const auto conversion = canonicalUnit(s.info.unit);
        if (!conversion)
            throw InputError(source, labels[i] + ".unit",
                             "unknown unit '" + s.info.unit +
                                 "' (1, %, 1/µm, 1/mm, 1/cm, 1/m, 1/nm or 1/sr)");
        s.info.unit = conversion->unit;
        if (conversion->factor != 1.0) {
            std::vector<double> values = s.spectrum.values();
            for (double& v : values) v *= conversion->factor;
            s.spectrum = Spectrum(s.spectrum.wavelengthsNm(), std::move(values));
        }
    }
}

}  // namespace detail

std::vector<NamedSpectrum> parseSpectraJson(std::string_view text_in, const std::string& source) {
    const Json document = jsonio::parseUntrustedJson(text_in, source);
    jsonio::ObjectReader r(document, "", source);
    if (r.string("format", true) != "paintlab-spectra") r.fail("format", "expected \"paintlab-spectra\"");
    if (r.number("format_version", "the format's version") != 1.0)
        r.fail("format_version", "only version 1 is known to this build");
    r.string("generated_by", false);
    const Json& list = r.require("spectra", "the spectra");
    if (!list.is_array()) r.fail("spectra", "expected an array");
    r.finish();
    std::vector<NamedSpectrum> out;
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string field = r.elementPath("spectra", i);
        jsonio::ObjectReader item(list[i], field, source);
        NamedSpectrum s;
        s.name = item.string("name", true);
        s.quantity = item.string("quantity", true);
        s.info = {item.string("unit", true), item.string("source", false), item.string("date", false)};
        auto wavelengths = item.numbers("wavelengths_nm");
        auto values = item.numbers("values");
        item.finish();
        s.spectrum = detail::checkedSpectrum(source, field, std::move(wavelengths), std::move(values));
        out.push_back(std::move(s));
        labels.push_back(field);
    }
    detail::finishNamedSpectra(out, labels, source);
    return out;
}

std::vector<NamedSpectrum> parseSpectraCsv(std::string_view text_in, const std::string& source) {
    const CsvTable table = CsvTable::parse(text_in, source);
    table.requireColumns({"name", "quantity", "unit", "wavelength_nm", "value"});
    table.allowOnlyColumns({"name", "quantity", "unit", "source", "date", "wavelength_nm", "value"});
    struct Gathered {
        std::vector<const CsvRecord*> records;
    };
    std::vector<std::string> order;
    std::map<std::string, Gathered> by_name;
    for (const auto& record : table.records()) {
        const std::string& name = table.field(record, "name");
        if (name.empty())
            throw InputError(source, CsvTable::where(record, "name"), "empty; every record needs a name");
        auto [it, added] = by_name.try_emplace(name);
        if (added) order.push_back(name);
        it->second.records.push_back(&record);
    }
    std::vector<NamedSpectrum> out;
    std::vector<std::string> labels;
    for (const auto& name : order) {
        const auto& records = by_name.at(name).records;
        const CsvRecord& first = *records.front();
        for (const auto column : {"quantity", "unit", "source", "date"})
            for (const auto* record : records)
                if (table.field(*record, column) != table.field(first, column))
                    throw InputError(source, CsvTable::where(*record, column),
                                     "'" + table.field(*record, column) + "' differs from '" +
                                         table.field(first, column) + "' on line " +
                                         std::to_string(first.line) + " of the same spectrum");
        std::vector<double> wavelengths;
        std::vector<double> values;
        for (const auto* record : records) {
            const double wavelength = table.requiredNumber(*record, "wavelength_nm");
            if (wavelength <= 0.0)
                throw InputError(source, CsvTable::where(*record, "wavelength_nm"),
                                 formatNumber(wavelength) + " nm: a wavelength must be positive");
            if (!wavelengths.empty() && wavelength <= wavelengths.back())
                throw InputError(source, CsvTable::where(*record, "wavelength_nm"),
                                 formatNumber(wavelength) + " nm does not increase on the previous " +
                                     formatNumber(wavelengths.back()) +
                                     " nm of the same spectrum (wavelengths must be strictly increasing)");
            wavelengths.push_back(wavelength);
            values.push_back(table.requiredNumber(*record, "value"));
        }
        NamedSpectrum s;
        s.name = name;
        s.quantity = table.field(first, "quantity");
        s.info = {table.field(first, "unit"), table.field(first, "source"), table.field(first, "date")};
        const std::string label = "line " + std::to_string(first.line) + " (spectrum '" + name + "')";
        s.spectrum = detail::checkedSpectrum(source, label, std::move(wavelengths), std::move(values));
        out.push_back(std::move(s));
        labels.push_back(label);
    }
    detail::finishNamedSpectra(out, labels, source);
    return out;
}

std::string spectraToJson(const std::vector<NamedSpectrum>& spectra) {
    nlohmann::ordered_json document{{"format", "paintlab-spectra"}, {"format_version", 1}};
    document["spectra"] = nlohmann::ordered_json::array();
    for (const auto& s : spectra) {
        nlohmann::ordered_json item{{"name", s.name},
                                    {"quantity", s.quantity},
                                    {"unit", s.info.unit},
                                    {"source", s.info.source},
                                    {"date", s.info.date},
                                    {"wavelengths_nm", s.spectrum.wavelengthsNm()},
                                    {"values", s.spectrum.values()}};
        document["spectra"].push_back(std::move(item));
    }
    return document.dump(2) + "\n";
}

std::string spectraToCsv(const std::vector<NamedSpectrum>& spectra) {
    std::string out = io::csvLine({"name", "quantity", "unit", "source", "date", "wavelength_nm", "value"});
    for (const auto& s : spectra)
        for (std::size_t i = 0; i < s.spectrum.values().size(); ++i)
            out += io::csvLine({s.name, s.quantity, s.info.unit, s.info.source, s.info.date,
                                io::csvNumber(s.spectrum.wavelengthsNm()[i]),
                                io::csvNumber(s.spectrum.values()[i])});
    return out;
}

}  // namespace paintlab::db
