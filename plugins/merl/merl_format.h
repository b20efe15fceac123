#pragma once
// The MERL BRDF binary (Matusik, Pfister, Brand, McMillan, "A Data-Driven
// Reflectance Model", SIGGRAPH 2003; the reader BRDFRead.cpp distributed with
// the MERL BRDF database): three little-endian int32 dimensions 90, 90, 180,
// then the R, G and B planes of 90 * 90 * 180 doubles each. Entry
// (theta_half index h, theta_diff index d, phi_diff index p) is at
// p + 180 (d + 90 h); an isotropic BRDF in Rusinkiewicz's half/difference
// angles, theta_half mapped non-linearly (h = floor(90 sqrt(theta_half / (pi/2)))),
// theta_diff linearly over [0, pi/2] and phi_diff over [0, pi) (reciprocity).
// Stored value x; f (1/sr) = x * scale, scales 1/1500, 1.15/1500, 1.66/1500
// for R, G, B. Negative entries mark what was not measured.

#include "paintlab/database/measurements.h"
#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace paintlab::plugins::merl {

inline constexpr int kThetaHalfBins = 90;
inline constexpr int kThetaDiffBins = 90;
inline constexpr int kPhiDiffBins = 180;
inline constexpr std::size_t kEntries = std::size_t{90} * 90 * 180;
inline constexpr std::size_t kHeaderBytes = 12;
inline constexpr std::size_t kFileBytes = kHeaderBytes + 3 * kEntries * sizeof(double);
inline constexpr std::array<double, 3> kScale = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
// Samples an import keeps unless told otherwise: enough for a fit of a few
// recipe parameters, few enough that each fast-model evaluation of them is quick.
inline constexpr std::size_t kDefaultSamples = 4096;

// Bins whose light or view direction is closer to the horizon than this
// cosine (0.06 degrees) are tabulated at it and not imported.
inline constexpr double kMinCosine = 1e-3;

struct BinIndex {
    int theta_half = 0;
    int theta_diff = 0;
    int phi_diff = 0;
};
std::size_t flatIndex(const BinIndex& bin);
BinIndex binOf(std::size_t flat);
// MERL's own look-up (BRDFRead.cpp) of half/difference angles in radians.
BinIndex lookup(double theta_half, double theta_diff, double phi_diff);
// The light and view directions at the centre of a bin (in the index space,
// so lookup() of its angles gives the bin back); phi_half = 0.
std::pair<Direction, Direction> binDirections(const BinIndex& bin);

// f per channel in 1/sr, plane by plane: rgb[c * kEntries + flat]; a
// negative value marks an entry that was not measured.
struct Table {
    std::vector<double> rgb = std::vector<double>(3 * kEntries, 0.0);
};

// The file's bytes.
std::string encode(const Table& table);
// Reads and checks a file: size, header, values (finite; negative only where
// unmeasured: MERL's -1 or a bin below the horizon). Throws InputError naming the file.
Table readFile(const std::filesystem::path& file);
Table decode(std::string_view bytes, const std::string& source);

// Every bin's f (called from several threads), evaluated at binDirections(); directions below kMinCosine
// are raised to it (renderers interpolate up to the horizon).
// progress (if set) gets the fraction of theta_half bins done; when it returns
// false the remaining bins are skipped and ExportCancelled is thrown.
Table tabulate(const std::function<Rgb(const Direction& wi, const Direction& wo)>& f,
               const ProgressCallback& progress = {});
// Linear sRGB (D65) of the spectral BRDF, mirror term excluded.
Table tabulate(const LayeredBrdf& brdf, const ProgressCallback& progress = {});

// A BRDF measurement from a table: channels R, G, B, at most max_samples
// measured bins with both direction cosines at least kMinCosine, evenly spread over
// the bins (all when max_samples >= their number; 0 means kDefaultSamples).
db::Measurement toMeasurement(const Table& table, std::size_t max_samples, db::Measurement description);

}  // namespace paintlab::plugins::merl
