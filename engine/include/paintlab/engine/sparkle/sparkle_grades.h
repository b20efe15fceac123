#pragma once
// Sparkle and graininess numbers from a sparkle texture (issue 7, "the
// sparkle grade and graininess-style numbers a lab instrument would
// report"). Instruments such as BYK-Gardner's BYK-mac i photograph the
// panel under directional LEDs (sparkle, at 15°, 45° and 75° aspecular)
// and under diffuse light (graininess) and report sparkle area S_a,
// sparkle intensity S_i, a sparkle grade S_G and a graininess G. Their
// exact image processing is proprietary: the numbers below are OURS, defined
// here, computed in the same spirit from the texture's elements (pixels),
// and are not claimed to equal an instrument's readings.
//
// For the element radiances v_i (i = 1..N, any unit) with mean m:
//   - sparkle_area_percent S_a = 100 * #{v_i > (1 + c) m} / N: the share of
//     elements that hold a glint at least c times brighter than the mean
//     (threshold contrast c, default 1: a glint doubles the element);
//   - sparkle_intensity S_i = mean of (v_i - m) / m over those elements: how
//     bright the glints are against the mean (0 when there are none);
//   - sparkle_grade S_G = sqrt(S_a * S_i): one number growing with both, the
//     geometric mean (the instrument's weighting is not published);
//   - contrast_cv = std(v) / m at the element's scale;
//   - graininess G = 100 * std / mean of the 2 x 2-element block means: the
//     light/dark pattern at twice the element's scale (what a diffuse-light
//     instrument sees at its coarser resolution), 0 for a uniform texture.

#include <span>

namespace paintlab {

struct SparkleGrades {
    double mean = 0.0;
    double sparkle_area_percent = 0.0;
    double sparkle_intensity = 0.0;
    double sparkle_grade = 0.0;
    double contrast_cv = 0.0;
    double graininess = 0.0;
    int elements = 0;
};

// values: width x height element radiances, row-major. Throws InputError
// ("<argument>") if the sizes disagree, an image side is under 2, a value is
// negative or not finite, or the threshold contrast is not positive.
SparkleGrades sparkleGrades(std::span<const double> values, int width, int height,
                            double threshold_contrast = 1.0);

}  // namespace paintlab
