#pragma once
// The spectral CGATS.17 (IT8.7) files that colord-data ships (cd-it8 "CMF"
// and "SPECT" files), read through the one CGATS parser (io/cgats.h, on
// liblcms2) and checked against their header: the grid from
// SPECTRAL_START_NM, SPECTRAL_END_NM and SPECTRAL_BANDS, SPEC_ fields only,
// every value finite and >= 0. Any mismatch throws paintlab::Error naming
// the file. Private to the engine: the public interface is cie_tables.h.

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
