#pragma once
// Relit image vs the brute-force reference, pixel by pixel, on the paint
// pixels of a ray map: a relative RMSE, the part of it the reference's own
// noise explains, and the excess that is the relight's error (with the
// precompute's own Monte Carlo noise in it). A failing comparison writes
// the relit image, the reference and their difference as EXR files into
// the working directory (next to the test log) and names them.

#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/reference.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace paintlab::raymaps::test {

struct PaintComparison {
    int pixels = 0;
    double mean_reference = 0.0;  // over the pixels and channels
    double rmse = 0.0;            // sqrt(mean (relit - reference)^2) / mean reference
    double noise = 0.0;           // sqrt(mean variance of the reference's mean) / mean reference
    // sqrt(max(0, mean d^2 - mean variance)) / mean reference: the RMSE the
    // reference's noise does not explain (E[d^2] = error^2 + variance).
    double excess = 0.0;
    Rgb3 bias = Rgb3::Zero();        // relative mean difference per channel
    Rgb3 bias_sigma = Rgb3::Zero();  // its standard error (reference noise)
};

// The paint pixels of `map` whose 8 neighbours are paint pixels too (every
// sample of the reference's pixel lands on paint) and that `keep` accepts
// (given the decoded record); a mask of width x height.
inline std::vector<char> interiorPaintMask(const RayMap& map,
                                           const std::function<bool(const PaintSample&)>& keep = {}) {
    const int w = map.header().width;
    const int h = map.header().height;
    std::vector<char> paint(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    std::vector<char> kept(paint.size(), 0);
    for (int b = 0; b < map.bandCount(); ++b) {
        const RayMapBand& band = map.band(b);
        for (std::size_t r = 0; r < band.record_count; ++r) {
            const PaintSample s = decodePaintSample(map, band, r);
            paint[s.pixel] = 1;
            kept[s.pixel] = (!keep || keep(s)) ? 1 : 0;
        }
    }
    std::vector<char> mask(paint.size(), 0);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            bool inside = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    inside = inside && paint[static_cast<std::size_t>((y + dy) * w + x + dx)] != 0;
            const auto at = static_cast<std::size_t>(y * w + x);
            mask[at] = inside && kept[at] != 0 ? 1 : 0;
        }
    return mask;
}

inline PaintComparison comparePaint(const RgbImage& relit, const ReferenceImage& reference,
                                    const std::vector<char>& mask) {
    PaintComparison out;
    double sum_d2 = 0.0;
    double sum_var = 0.0;
    double sum_ref = 0.0;
    Rgb3 diff = Rgb3::Zero();
    Rgb3 ref = Rgb3::Zero();
    Rgb3 var = Rgb3::Zero();
    for (std::size_t p = 0; p < mask.size(); ++p) {
        if (mask[p] == 0) continue;
        ++out.pixels;
        for (int c = 0; c < 3; ++c) {
            const std::size_t at = 3 * p + static_cast<std::size_t>(c);
            const double d = static_cast<double>(relit.rgb[at]) - static_cast<double>(reference.mean.rgb[at]);
            sum_d2 += d * d;
            sum_var += static_cast<double>(reference.variance_of_mean[at]);
            sum_ref += static_cast<double>(reference.mean.rgb[at]);
            diff[c] += d;
            ref[c] += static_cast<double>(reference.mean.rgb[at]);
            var[c] += static_cast<double>(reference.variance_of_mean[at]);
        }
    }
    if (out.pixels == 0) return out;
    const double n = 3.0 * out.pixels;
    out.mean_reference = sum_ref / n;
    out.rmse = std::sqrt(sum_d2 / n) / out.mean_reference;
    out.noise = std::sqrt(sum_var / n) / out.mean_reference;
    out.excess = std::sqrt(std::max(0.0, sum_d2 - sum_var) / n) / out.mean_reference;
    for (int c = 0; c < 3; ++c) {
        out.bias[c] = diff[c] / ref[c];
        out.bias_sigma[c] = std::sqrt(var[c]) / ref[c];
    }
    return out;
}

inline void printComparison(const char* what, const PaintComparison& c) {
    std::printf("%s: %d paint pixels, RMSE %.2f %% (reference noise %.2f %%, excess %.2f %%), "
                "bias %+.2f / %+.2f / %+.2f %% (sigma %.2f / %.2f / %.2f %%)\n",
                what, c.pixels, 100 * c.rmse, 100 * c.noise, 100 * c.excess, 100 * c.bias[0], 100 * c.bias[1],
                100 * c.bias[2], 100 * c.bias_sigma[0], 100 * c.bias_sigma[1], 100 * c.bias_sigma[2]);
}

// Writes <name>_relit.exr, <name>_reference.exr and <name>_difference.exr
// (relit - reference, linear) into the working directory; returns their folder.
inline std::filesystem::path writeComparisonImages(const std::string& name, const RgbImage& relit,
                                                   const ReferenceImage& reference) {
    RgbImage difference = relit;
    for (std::size_t i = 0; i < difference.rgb.size(); ++i) difference.rgb[i] -= reference.mean.rgb[i];
    const auto folder = std::filesystem::current_path();
    writeImage(relit, folder / (name + "_relit.exr"));
    writeImage(reference.mean, folder / (name + "_reference.exr"));
    writeImage(difference, folder / (name + "_difference.exr"));
    std::printf("wrote %s/%s_{relit,reference,difference}.exr\n", folder.string().c_str(), name.c_str());
    return folder;
}

}  // namespace paintlab::raymaps::test
