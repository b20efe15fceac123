#pragma once
// CIE standard observers and illuminants, read at run time from the CGATS
// tables of Debian's colord-data package (no table is copied into the source),
// and the spectral integration built on them (CIE 15:2004, section 7).
//
// Files, under colordDataDir():
//   cmf/CIE1931-2deg-XYZ.cmf, cmf/CIE1964-10deg-XYZ.cmf   360-830 nm, 5 nm
//   illuminant/CIE-D65.sp (300-830 nm, 5 nm), CIE-D50.sp (380-780 nm, 5 nm),
//   illuminant/CIE-A.sp (300-830 nm, 1 nm)
// Each table is read once, on first use, and cached for the life of the
// process (function-local statics: thread-safe, and a failed load is retried
// on the next call rather than cached).

#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/spectrum.h"

#include <filesystem>
#include <string_view>

namespace paintlab {

enum class Observer { Cie1931_2deg, Cie1964_10deg };
enum class Illuminant { D65, D50, A };

std::string_view toString(Observer observer) noexcept;
std::string_view toString(Illuminant illuminant) noexcept;

// x-bar, y-bar, z-bar on one wavelength grid (that of the file).
struct ColourMatchingFunctions {
    Spectrum xBar;
    Spectrum yBar;
    Spectrum zBar;
};

// $PAINTLAB_COLORD_DIR if set and not empty, else /usr/share/colord.
// Read on every call; the cached tables keep the directory of their first use.
std::filesystem::path colordDataDir();
std::filesystem::path cmfFilePath(Observer observer);
std::filesystem::path illuminantFilePath(Illuminant illuminant);

// Uncached readers of one colord CGATS file. The wavelength grid comes from
// SPECTRAL_START_NM, SPECTRAL_END_NM and SPECTRAL_BANDS. Throw paintlab::Error
// naming the file (and the line, where there is one) if it is missing,
// unreadable, truncated, or holds anything but one (.sp) or three (.cmf) sets
// of finite, non-negative numbers matching its header.
ColourMatchingFunctions readCmfFile(const std::filesystem::path& file);
Spectrum readSpectrumFile(const std::filesystem::path& file);

// Cached tables. Throw paintlab::Error (from the readers) if the file cannot
// be loaded; never after a first successful call.
const ColourMatchingFunctions& cmf(Observer observer);
// Relative spectral power, as in the file (colord scales S(560 nm) to 1).
const Spectrum& illuminantSpd(Illuminant illuminant);

// The illuminant's white, Y = 1: X = sum S x-bar / sum S y-bar, Z likewise,
// summed at the observer's tabulated wavelengths (5 nm, 360-830 nm) where the
// illuminant is tabulated (CIE 15:2004 section 7.1, the integrals taken as sums).
// Throws paintlab::Error if a table cannot be loaded.
Xyz whitePoint(Illuminant illuminant, Observer observer);

// Tristimulus values of a reflecting (or transmitting) object, normalised so
// that a perfect white gives Y = 1: X = k sum R S x-bar, k = 1 / sum S y-bar,
// over the same wavelengths as whitePoint. The reflectance is sampled as a
// Spectrum (linear between its samples, its end values held beyond them, which
// is CIE 15:2004's advice for data not covering the whole range).
// Throws paintlab::Error if a table cannot be loaded.
Xyz reflectanceToXyz(const Spectrum& reflectance, Illuminant illuminant, Observer observer);

}  // namespace paintlab
