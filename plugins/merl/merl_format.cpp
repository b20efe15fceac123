// The MERL BRDF binary (merl_format.h).

#include "merl_format.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/plugin.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>
#include <system_error>

#include <tbb/parallel_for.h>

namespace paintlab::plugins::merl {

static_assert(std::endian::native == std::endian::little,
              "the MERL file is little-endian, as this host must be");

namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;
constexpr std::array<const char*, 3> kChannels = {"R", "G", "B"};

std::string binName(std::size_t channel, std::size_t flat) {
    const BinIndex bin = binOf(flat);
    return std::string(kChannels[channel]) + "[theta_half " + std::to_string(bin.theta_half) +
           ", theta_diff " + std::to_string(bin.theta_diff) + ", phi_diff " + std::to_string(bin.phi_diff) +
           "]";
}

bool belowHorizon(std::size_t flat) {
    const auto [wi, wo] = binDirections(binOf(flat));
    return wi.z <= 0.0 || wo.z <= 0.0;
}

Direction raised(Direction v) {
    if (v.z >= kMinCosine) return v;
    const double xy = std::hypot(v.x, v.y);
    const double s = std::sqrt(1.0 - kMinCosine * kMinCosine) / xy;
    return {v.x * s, v.y * s, kMinCosine};
}

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

}  // namespace

std::size_t flatIndex(const BinIndex& bin) {
    return static_cast<std::size_t>(bin.phi_diff) +
           static_cast<std::size_t>(kPhiDiffBins) *
               (static_cast<std::size_t>(bin.theta_diff) +
                static_cast<std::size_t>(kThetaDiffBins) * static_cast<std::size_t>(bin.theta_half));
}

BinIndex binOf(std::size_t flat) {
    BinIndex bin;
    bin.phi_diff = static_cast<int>(flat % kPhiDiffBins);
    bin.theta_diff = static_cast<int>((flat / kPhiDiffBins) % kThetaDiffBins);
    bin.theta_half = static_cast<int>(flat / (static_cast<std::size_t>(kPhiDiffBins) * kThetaDiffBins));
    return bin;
}

BinIndex lookup(double theta_half, double theta_diff, double phi_diff) {
    BinIndex bin;
    if (theta_half > 0.0)
        bin.theta_half =
            std::clamp(static_cast<int>(std::sqrt(theta_half / kHalfPi * kThetaHalfBins * kThetaHalfBins)), 0,
                       kThetaHalfBins - 1);
    bin.theta_diff =
        std::clamp(static_cast<int>(theta_diff / kHalfPi * kThetaDiffBins), 0, kThetaDiffBins - 1);
    if (phi_diff < 0.0) phi_diff += std::numbers::pi;  // reciprocity
    bin.phi_diff =
        std::clamp(static_cast<int>(phi_diff / std::numbers::pi * kPhiDiffBins), 0, kPhiDiffBins - 1);
    return bin;
}

std::pair<Direction, Direction> binDirections(const BinIndex& bin) {
    const double u = (bin.theta_half + 0.5) / kThetaHalfBins;
    const double theta_half = u * u * kHalfPi;
    const double theta_diff = (bin.theta_diff + 0.5) / kThetaDiffBins * kHalfPi;
    const double phi_diff = (bin.phi_diff + 0.5) / kPhiDiffBins * std::numbers::pi;
    // The difference vector rotated by theta_half about the binormal (y), as
    // BRDFRead.cpp's half_diff_coords_to_std_coords with phi_half = 0.
    const double dx = std::sin(theta_diff) * std::cos(phi_diff);
    const double dy = std::sin(theta_diff) * std::sin(phi_diff);
    const double dz = std::cos(theta_diff);
    const double ch = std::cos(theta_half);
    const double sh = std::sin(theta_half);
    const Direction wi{dx * ch + dz * sh, dy, dz * ch - dx * sh};
    const Direction h{sh, 0.0, ch};
    const double k = 2.0 * (wi.x * h.x + wi.y * h.y + wi.z * h.z);
    const Direction wo{k * h.x - wi.x, k * h.y - wi.y, k * h.z - wi.z};
    return {wi, wo};
}

std::string encode(const Table& table) {
    std::string bytes(kFileBytes, '\0');
    const std::array<std::int32_t, 3> dims = {kThetaHalfBins, kThetaDiffBins, kPhiDiffBins};
    std::memcpy(bytes.data(), dims.data(), kHeaderBytes);
    std::vector<double> stored(table.rgb.size());
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < kEntries; ++i) {
            const double f = table.rgb[c * kEntries + i];
            stored[c * kEntries + i] = f < 0.0 ? -1.0 : f / kScale[c];
        }
    std::memcpy(bytes.data() + kHeaderBytes, stored.data(), stored.size() * sizeof(double));
    return bytes;
}

namespace {

// The three dimensions first: a wrong header is named before a wrong size.
void checkHeader(std::string_view bytes, const std::string& source) {
    if (bytes.size() < kHeaderBytes)
        throw InputError(source, "header",
                         "truncated: " + std::to_string(bytes.size()) +
                             " bytes, a MERL BRDF file starts with three 4-byte dimensions");
    std::array<std::int32_t, 3> dims{};
    std::memcpy(dims.data(), bytes.data(), kHeaderBytes);
    if (dims[0] != kThetaHalfBins || dims[1] != kThetaDiffBins || dims[2] != kPhiDiffBins) {
        std::ostringstream claimed;  // up to 2^93: as a double, "1e+12"
        claimed << static_cast<double>(dims[0]) * dims[1] * dims[2];
        throw InputError(source, "header",
                         "dimensions " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                             std::to_string(dims[2]) + " (" + claimed.str() +
                             " samples per channel); a MERL BRDF file has 90 x 90 x 180");
    }
}

void checkSize(std::uintmax_t size, const std::string& source) {
    if (size != kFileBytes)
        throw InputError(source, "",
                         "the file has " + std::to_string(size) + " bytes; a 90 x 90 x 180 MERL file has " +
                             std::to_string(kFileBytes) + (size < kFileBytes ? " (truncated)" : ""));
}

}  // namespace

Table decode(std::string_view bytes, const std::string& source) {
    checkHeader(bytes, source);
    checkSize(bytes.size(), source);
    Table table;
    std::memcpy(table.rgb.data(), bytes.data() + kHeaderBytes, table.rgb.size() * sizeof(double));
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < kEntries; ++i) {
            double& value = table.rgb[c * kEntries + i];
            if (!std::isfinite(value)) throw InputError(source, binName(c, i), "is not a finite number");
            if (value < 0.0) {
                if (value != -1.0 && !belowHorizon(i))
                    throw InputError(source, binName(c, i),
                                     "is negative (" + std::to_string(value) +
                                         "); f must be >= 0, and MERL marks an unmeasured entry with -1");
                value = -1.0;
                continue;
            }
            value *= kScale[c];
        }
    return table;
}

Table readFile(const std::filesystem::path& file) {
    const std::string source = file.string();
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(file, error);
    if (error) throw InputError(source, "", "cannot read the file: " + error.message());
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(source, "", "cannot open the file");
    // Never more than a MERL file's size: a longer file is refused by its size.
    const std::size_t wanted = size == kFileBytes ? kFileBytes : std::min<std::size_t>(size, kHeaderBytes);
    std::string bytes(wanted, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(wanted));
    if (static_cast<std::size_t>(in.gcount()) != wanted) throw InputError(source, "", "read error");
    if (size != kFileBytes) {
        checkHeader(bytes, source);
        checkSize(size, source);
    }
    return decode(bytes, source);
}

Table tabulate(const std::function<Rgb(const Direction& wi, const Direction& wo)>& f,
               const ProgressCallback& progress) {
    Table table;
    // One task per theta_half bin (16,200 entries each); f is called from several threads.
    constexpr std::size_t kPerThetaHalf = kEntries / kThetaHalfBins;
    std::atomic<int> done{0};
    std::atomic<bool> stop{false};
    tbb::parallel_for(0, kThetaHalfBins, [&](int h) {
        if (stop.load()) return;
        const std::size_t begin = static_cast<std::size_t>(h) * kPerThetaHalf;
        for (std::size_t i = begin; i < begin + kPerThetaHalf; ++i) {
            const auto [wi, wo] = binDirections(binOf(i));
            const Rgb rgb = f(raised(wi), raised(wo));
            table.rgb[i] = rgb.r;
            table.rgb[kEntries + i] = rgb.g;
            table.rgb[2 * kEntries + i] = rgb.b;
        }
        const double fraction = static_cast<double>(++done) / kThetaHalfBins;
        if (progress && !progress(fraction)) stop = true;
    });
    if (stop.load()) throw ExportCancelled();
    return table;
}

Table tabulate(const LayeredBrdf& brdf, const ProgressCallback& progress) {
    const BandColourWeights weights = bandColourWeights(brdf.wavelengthsNm());
    const std::size_t bands = brdf.wavelengthsNm().size();
    return tabulate(
        [&](const Direction& wi, const Direction& wo) {
            std::vector<double> spectrum(bands);  // per call: eval runs on several threads
            brdf.eval(wi, wo, spectrum);
            return weightedLinearSrgb(weights, spectrum);
        },
        progress);
}

db::Measurement toMeasurement(const Table& table, std::size_t max_samples, db::Measurement description) {
    std::vector<std::size_t> measured;
    for (std::size_t i = 0; i < kEntries; ++i) {
        if (table.rgb[i] < 0.0 || table.rgb[kEntries + i] < 0.0 || table.rgb[2 * kEntries + i] < 0.0)
            continue;
        const auto [wi, wo] = binDirections(binOf(i));
        if (wi.z < kMinCosine || wo.z < kMinCosine) continue;
        measured.push_back(i);
    }
    const std::size_t wanted = std::min(max_samples == 0 ? kDefaultSamples : max_samples, measured.size());
    db::Measurement m = std::move(description);
    m.kind = db::MeasurementKind::Brdf;
    m.channels = {"R", "G", "B"};
    m.wavelengths_nm.clear();
    m.readings.clear();
    m.samples.clear();
    m.samples.reserve(wanted);
    for (std::size_t k = 0; k < wanted; ++k) {
        // Evenly over the measured bins; the index space is already denser
        // near the specular peak (theta_half is mapped by a square root).
        const std::size_t i = measured[k * measured.size() / wanted];
        const auto [wi, wo] = binDirections(binOf(i));
        db::BrdfSample s;
        s.theta_i_deg = degrees(std::acos(std::clamp(wi.z, -1.0, 1.0)));
        s.phi_i_deg = degrees(std::atan2(wi.y, wi.x));
        s.theta_o_deg = degrees(std::acos(std::clamp(wo.z, -1.0, 1.0)));
        s.phi_o_deg = degrees(std::atan2(wo.y, wo.x));
        s.values = {table.rgb[i], table.rgb[kEntries + i], table.rgb[2 * kEntries + i]};
        m.samples.push_back(std::move(s));
    }
    return m;
}

}  // namespace paintlab::plugins::merl
