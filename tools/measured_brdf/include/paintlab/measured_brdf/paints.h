#pragma once
// The measured paints of shared/data/measured-brdf: each neural fit with the
// published analytic fits of the same MERL material (RGL materials have none),
// and their colours at the six multi-angle geometries.

#include "paintlab/measured_brdf/analytic_brdf.h"
#include "paintlab/measured_brdf/neural_brdf.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace paintlab::measured {

struct MeasuredPaint {
    NeuralBrdf neural;  // the reference: name() is the file's key, "MERL/pearl-paint"
    std::string stem;   // for file names: "merl-pearl-paint"
    std::optional<AbcBrdf> abc;
    std::optional<SgdBrdf> sgd;
};

// Reads nbrdf_paints.json, merl_abc_low2012_params.csv and
// merl_sgd_bagher2012_params.csv from dir. Throws InputError as the loaders.
std::vector<MeasuredPaint> loadMeasuredPaints(const std::filesystem::path& dir);

// CIELAB of pi f at the six multi-angle geometries (multiangle.h order:
// 45as-15, 15, 25, 45, 75, 110), linear sRGB to Lab as reflectanceFactorLab.
std::array<Lab, 6> multiAngleLabs(const RgbBrdf& brdf);

}  // namespace paintlab::measured
