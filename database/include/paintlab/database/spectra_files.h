#pragma once
// Files of spectra stored on their own (a measured reflectance, a
// spectrophotometer's export), each with a unique name:
//
// - JSON: { "format": "paintlab-spectra", "format_version": 1, "spectra": [
//           { "name": "...", "quantity": "reflectance", "unit": "1", "source": "...",
//             "date": "...", "wavelengths_nm": [...], "values": [...] } ] }
// - CSV:  columns name, quantity, unit, source, date, wavelength_nm, value;
//         one record per sample, the samples of a spectrum in increasing wavelength.
// - CGATS.17 / IT8.7 text, as spectrophotometers export it (parsed by
//   liblcms2's cmsIT8): one row per measured sample, named by SAMPLE_NAME
//   (else SAMPLE_ID, else "<file stem> <row>"), one column per wavelength
//   (SPECTRAL_NM380, SPECTRAL_NM_380, SPECTRAL_380, NM380, SPEC_380, R380, ...).
//   The quantity and unit come from the keywords PAINTLAB_QUANTITY and
//   PAINTLAB_UNIT when the file has them (PaintLab writes them), else from
//   CgatsOptions; source and date from ORIGINATOR/INSTRUMENTATION and CREATED.
//
// Units are converted to the canonical ones ("%" -> "1", "1/cm" -> "1/µm";
// spectrum_checks.h lists them); an unknown unit is an error.

#include "paintlab/database/ingredients.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

struct NamedSpectrum {
    std::string name;
    std::string quantity;  // "reflectance", "transmittance", "k_over_s", ...
    SpectrumInfo info;
    Spectrum spectrum;
    friend bool operator==(const NamedSpectrum&, const NamedSpectrum&) = default;
};

struct CgatsOptions {
    std::string quantity = "reflectance";
    // The unit of the values ("1" or "%"). Empty: "1", but a file whose values
    // go above 2 is refused (reflectance in percent?) until the unit is given.
    std::string unit;
    std::string source;  // overrides the source taken from the file's keywords
};

// Each throws InputError naming source, the record (line, spectra[i] or CGATS
// row) and the field: malformed or truncated file, missing column, a number
// that is not finite, a wavelength <= 0 or not increasing, unknown unit, a
// name that is empty or appears twice.
std::vector<NamedSpectrum> parseSpectraJson(std::string_view text, const std::string& source);
std::vector<NamedSpectrum> parseSpectraCsv(std::string_view text, const std::string& source);
std::vector<NamedSpectrum> parseSpectraCgats(std::string_view text, const std::string& source,
                                             const CgatsOptions& options = {});

// The wavelength (nm) of a CGATS spectral column name (SPECTRAL_NM380,
// SPECTRAL_NM_380, SPECTRAL_380, SPEC_380, NM380, R380, ...; any case), or
// nullopt if the name is not one. Never throws.
std::optional<double> cgatsSpectralWavelength(std::string_view column);

std::string spectraToJson(const std::vector<NamedSpectrum>& spectra);
std::string spectraToCsv(const std::vector<NamedSpectrum>& spectra);
// One CGATS table: every spectrum must share the wavelength grid, quantity
// and unit, and no name may hold a double quote (CGATS strings cannot); else
// InputError (export as CSV or JSON instead).
std::string spectraToCgats(const std::vector<NamedSpectrum>& spectra);

}  // namespace paintlab::db
