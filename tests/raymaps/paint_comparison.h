#pragma once
// Relit image vs the brute-force reference, pixel by pixel, on the paint
// pixels of a ray map: a relative RMSE, the parts of it that the reference's
// own noise and the precompute's own noise explain, and what is left, the
// relight's systematic error (moment truncation, paint proxy, one frame per
// pixel, table interpolation). E[d^2] = error^2 + var(reference) +
// var(relit); var(relit) per pixel is estimated from a second ray map of
// another seed: E[(R1 - R2)^2] / 2. A failing comparison writes
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

namespace paintlab::raymaps::compare {

struct PaintComparison {
    int pixels = 0;
    double mean_reference = 0.0;  // over the pixels and channels
    double rmse = 0.0;            // sqrt(mean (relit - reference)^2) / mean reference
    double noise = 0.0;           // sqrt(mean variance of the reference's mean) / mean reference
    double relit_noise = 0.0;     // sqrt(mean var(relit)) / mean reference (0 without a second map)
    // sqrt(max(0, mean d^2 - mean var(reference))) / mean reference: the
    // relit image's RMSE against the truth, the precompute's noise included.
    double excess = 0.0;
    // The same without the precompute's noise: the systematic error.
    double systematic = 0.0;
    // Standard error of systematic^2 as estimated (d^2 of a Gaussian
    // difference of variance v has variance 2 v^2 when the error is small):
    // the resolution of the test, which the references' samples limit.
    double systematic2_sigma = 0.0;
    Rgb3 bias = Rgb3::Zero();        // relative mean difference per channel
    Rgb3 bias_sigma = Rgb3::Zero();  // its standard error (reference noise)
};

// The paint pixels of `map` whose 8 neighbours are paint pixels too (every
// sample of the reference's pixel lands on paint), whose neighbours' normals
// lie within 15 degrees of their own (no crease between two paint surfaces
// inside the pixel, where one frame per pixel is a documented
// approximation), and that `keep` accepts (given the decoded record); a
// mask of width x height.
inline std::vector<char> interiorPaintMask(const RayMap& map,
                                           const std::function<bool(const PaintSample&)>& keep = {}) {
    const float kCosCrease = std::cos(15.0F * 3.14159265F / 180.0F);
    const int w = map.header().width;
    const int h = map.header().height;
    std::vector<char> paint(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    std::vector<char> kept(paint.size(), 0);
    std::vector<Eigen::Vector3f> normal(paint.size(), Eigen::Vector3f::Zero());
    for (int b = 0; b < map.bandCount(); ++b) {
        const RayMapBand& band = map.band(b);
        for (std::size_t r = 0; r < band.record_count; ++r) {
            const PaintSample s = decodePaintSample(map, band, r);
            paint[s.pixel] = 1;
            normal[s.pixel] = s.normal;
            kept[s.pixel] = (!keep || keep(s)) ? 1 : 0;
        }
    }
    std::vector<char> mask(paint.size(), 0);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            bool inside = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto q = static_cast<std::size_t>((y + dy) * w + x + dx);
                    inside = inside && paint[q] != 0 &&
                             normal[q].dot(normal[static_cast<std::size_t>(y * w + x)]) > kCosCrease;
                }
            const auto at = static_cast<std::size_t>(y * w + x);
            mask[at] = inside && kept[at] != 0 ? 1 : 0;
        }
    return mask;
}

// `relit_b`: the relight of a second map of another seed (empty: no
// precompute-noise estimate).
// Pixels whose clear-coat mirror direction passes within `degrees` of a sun
// are the sun's glint: a subpixel image of a 0.5-degree disk, found by one
// mirror ray of the precompute or by chance in the reference. Like sparkle,
// it is no part of the smooth-shading budget; this predicate leaves it out.
// `sun_images`: further directions (unit, towards them) where a sun is seen,
// e.g. its image in a plane mirror of the scene, whose glints in the coat
// are left out the same way.
inline std::function<bool(const PaintSample&)>
notSunGlint(const RayMap& map, double degrees, const std::function<bool(const PaintSample&)>& and_also = {},
            const std::vector<Eigen::Vector3f>& sun_images = {}) {
    std::vector<Eigen::Vector3f> suns = sun_images;
    for (const ExplicitLight& l : map.header().lights)
        if (l.kind == ExplicitLight::Kind::Sun) suns.push_back(l.vector.cast<float>());
    const auto cos_limit = static_cast<float>(std::cos(degrees * 3.14159265358979 / 180.0));
    return [suns, cos_limit, and_also](const PaintSample& s) {
        const Eigen::Vector3f r = 2.0F * s.normal.dot(s.view) * s.normal - s.view;
        for (const auto& sun : suns)
            if (r.dot(sun) > cos_limit) return false;
        return !and_also || and_also(s);
    };
}

inline PaintComparison comparePaint(const RgbImage& relit, const ReferenceImage& reference,
                                    const std::vector<char>& mask, const RgbImage& relit_b = {}) {
    PaintComparison out;
    double sum_d2 = 0.0;
    double sum_var = 0.0;
    double sum_var_relit = 0.0;
    double sum_var2 = 0.0;  // sum of 2 v^2
    const bool second = relit_b.rgb.size() == relit.rgb.size();
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
            double v = static_cast<double>(reference.variance_of_mean[at]);
            if (second) {
                const double e = static_cast<double>(relit.rgb[at]) - static_cast<double>(relit_b.rgb[at]);
                sum_var_relit += 0.5 * e * e;
                v += 0.5 * e * e;
            }
            sum_var2 += 2.0 * v * v;
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
    out.relit_noise = std::sqrt(sum_var_relit / n) / out.mean_reference;
    out.excess = std::sqrt(std::max(0.0, sum_d2 - sum_var) / n) / out.mean_reference;
    out.systematic = std::sqrt(std::max(0.0, sum_d2 - sum_var - sum_var_relit) / n) / out.mean_reference;
    out.systematic2_sigma = std::sqrt(sum_var2) / n / (out.mean_reference * out.mean_reference);
    for (int c = 0; c < 3; ++c) {
        out.bias[c] = diff[c] / ref[c];
        out.bias_sigma[c] = std::sqrt(var[c]) / ref[c];
    }
    return out;
}

// The precompute's noise seen in two relights of maps traced with different
// seeds (same scene, settings and recipe), over the pixels of `mask`, per
// channel: the RMS of the per-pixel relative difference (a - b) / ((a + b) / 2)
// and, less sensitive to dark pixels, RMS(a - b) / mean((a + b) / 2). Both are
// of a difference of two independent estimates: divide by sqrt(2) for one
// map's noise (`perMap`). Channel values whose mean is not above
// `floor` x the channel's mean over the mask are left out of the per-pixel
// figure (they count in the other).
struct SeedNoise {
    int pixels = 0;
    Rgb3 relative = Rgb3::Zero();  // RMS of the per-pixel relative difference
    Rgb3 of_mean = Rgb3::Zero();   // RMS difference / mean
    static double perMap(double difference) { return difference / std::sqrt(2.0); }
};

inline SeedNoise seedNoise(const RgbImage& a, const RgbImage& b, const std::vector<char>& mask,
                           double floor = 1e-3) {
    SeedNoise out;
    Rgb3 mean = Rgb3::Zero();
    for (std::size_t p = 0; p < mask.size(); ++p) {
        if (mask[p] == 0) continue;
        ++out.pixels;
        for (int c = 0; c < 3; ++c) {
            const std::size_t at = 3 * p + static_cast<std::size_t>(c);
            mean[c] += 0.5 * (static_cast<double>(a.rgb[at]) + static_cast<double>(b.rgb[at]));
        }
    }
    if (out.pixels == 0) return out;
    mean /= out.pixels;
    Rgb3 d2 = Rgb3::Zero();
    Rgb3 r2 = Rgb3::Zero();
    Eigen::Vector3i counted = Eigen::Vector3i::Zero();
    for (std::size_t p = 0; p < mask.size(); ++p) {
        if (mask[p] == 0) continue;
        for (int c = 0; c < 3; ++c) {
            const std::size_t at = 3 * p + static_cast<std::size_t>(c);
            const double x = static_cast<double>(a.rgb[at]);
            const double y = static_cast<double>(b.rgb[at]);
            d2[c] += (x - y) * (x - y);
            const double m = 0.5 * (x + y);
            if (!(m > floor * mean[c])) continue;
            r2[c] += (x - y) * (x - y) / (m * m);
            ++counted[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        out.of_mean[c] = mean[c] > 0.0 ? std::sqrt(d2[c] / out.pixels) / mean[c] : 0.0;
        out.relative[c] = counted[c] > 0 ? std::sqrt(r2[c] / counted[c]) : 0.0;
    }
    return out;
}

inline void printComparison(const char* what, const PaintComparison& c) {
    std::printf("%s: %d paint pixels, RMSE %.2f %% (reference noise %.2f %%, precompute noise %.2f %%; "
                "against the truth %.2f %%, systematic %.2f %%, at most %.2f %% at 3 sigma), bias %+.2f / "
                "%+.2f / %+.2f %% "
                "(sigma %.2f / %.2f / %.2f %%)\n",
                what, c.pixels, 100 * c.rmse, 100 * c.noise, 100 * c.relit_noise, 100 * c.excess,
                100 * c.systematic, 100 * std::sqrt(c.systematic * c.systematic + 3.0 * c.systematic2_sigma),
                100 * c.bias[0], 100 * c.bias[1], 100 * c.bias[2], 100 * c.bias_sigma[0],
                100 * c.bias_sigma[1], 100 * c.bias_sigma[2]);
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

}  // namespace paintlab::raymaps::compare
