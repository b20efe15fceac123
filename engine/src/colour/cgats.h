#pragma once
// A reader for the spectral CGATS.17 (IT8.7) text files that colord-data
// ships (cd-it8 "CMF" and "SPECT" files). It understands the subset those
// files use: a file identifier line, KEYWORD value lines, one
// BEGIN_DATA_FORMAT/END_DATA_FORMAT block of field names, one
// BEGIN_DATA/END_DATA block of numbers, and '#' comments. Everything is
// checked against the header; any mismatch throws paintlab::Error naming the
// file. Private to the engine: the public interface is cie_tables.h.

#include <filesystem>
#include <vector>

namespace paintlab::cgats {

struct SpectralTable {
    std::vector<double> wavelengths_nm;     // SPECTRAL_BANDS values, uniform, increasing
    std::vector<std::vector<double>> sets;  // NUMBER_OF_SETS rows of SPECTRAL_BANDS values
};

// Reads a colord spectral CGATS file holding exactly expected_sets data sets
// (1 for an illuminant, 3 for colour matching functions). Every value must be
// finite and >= 0: these are powers and colour matching functions.
SpectralTable readSpectralTable(const std::filesystem::path& file, std::size_t expected_sets);

}  // namespace paintlab::cgats
