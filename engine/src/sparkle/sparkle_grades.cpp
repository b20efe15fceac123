// Sparkle area, intensity, grade and graininess of a texture (definitions in sparkle_grades.h).

#include "paintlab/engine/sparkle/sparkle_grades.h"

#include "paintlab/engine/error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace paintlab {

namespace {

// std / mean, two-pass (a one-pass sum of squares cancels badly for a flat texture).
double coefficientOfVariation(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    const double mean = sum / static_cast<double>(v.size());
    if (!(mean > 0.0)) return 0.0;
    double sq = 0.0;
    for (double x : v) sq += (x - mean) * (x - mean);
    return std::sqrt(sq / static_cast<double>(v.size())) / mean;
}

}  // namespace

SparkleGrades sparkleGrades(std::span<const double> values, int width, int height,
                            double threshold_contrast) {
    if (width < 2 || height < 2)
        throw InputError("<argument>", "texture size",
                         std::to_string(width) + " x " + std::to_string(height) + ": each side must be >= 2");
    if (values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw InputError("<argument>", "texture values",
                         std::to_string(values.size()) + " values for " + std::to_string(width) + " x " +
                             std::to_string(height) + " elements");
    if (!(threshold_contrast > 0.0))
        throw InputError("<argument>", "threshold_contrast",
                         std::to_string(threshold_contrast) + " must be > 0");
    double sum = 0.0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = values[i];
        if (!std::isfinite(v) || v < 0.0)
            throw InputError("<argument>", "texture values",
                             "element " + std::to_string(i) + " is " + std::to_string(v) + " (must be >= 0)");
        sum += v;
    }
    SparkleGrades g;
    g.elements = static_cast<int>(values.size());
    const auto count = static_cast<double>(values.size());
    g.mean = sum / count;
    if (!(g.mean > 0.0)) return g;
    g.contrast_cv = coefficientOfVariation(std::vector<double>(values.begin(), values.end()));

    const double threshold = (1.0 + threshold_contrast) * g.mean;
    double above = 0.0;
    double contrast_sum = 0.0;
    for (double v : values)
        if (v > threshold) {
            above += 1.0;
            contrast_sum += (v - g.mean) / g.mean;
        }
    g.sparkle_area_percent = 100.0 * above / count;
    g.sparkle_intensity = above > 0.0 ? contrast_sum / above : 0.0;
    g.sparkle_grade = std::sqrt(g.sparkle_area_percent * g.sparkle_intensity);

    std::vector<double> blocks;
    for (int y = 0; y + 1 < height; y += 2)
        for (int x = 0; x + 1 < width; x += 2) {
            const auto at = [&](int xx, int yy) {
                return values[static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(xx)];
            };
            const double b = 0.25 * (at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1));
            blocks.push_back(b);
        }
    g.graininess = 100.0 * coefficientOfVariation(blocks);
    return g;
}

}  // namespace paintlab
