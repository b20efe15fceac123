#pragma once
// The neural BRDFs of shared/data/measured-brdf/nbrdf_paints.json
// (Sztrajman, Rainer, Weyrich, "Neural BRDF Representation and Importance
// Sampling", CGF 2021): per material an MLP 6-21-21-3 of Rusinkiewicz's
// half and difference vectors (phi_h = 0, so isotropic by construction):
//   x  = (sin θh, 0, cos θh, d.x, d.y, d.z), d = wi rotated by -φh about z, -θh about y
//   h1 = relu(x W1 + b1), h2 = relu(h1 W2 + b2), y = h2 W3 + b3
//   f  = exp(y) - 1 (RGB, 1/sr), clamped at 0 (the authors' renderer does the same).
//
// Colour scale. MERL materials: the networks were trained on MERL values read
// with MERL's per-channel scale factors already applied (1/1500, 1.15/1500,
// 1.66/1500: the training reads the binary through a reader that multiplies
// by them, and the white paint's 0.11 1/sr agrees with the analytic fits made
// on the scaled data), so nothing is scaled again here. MERL's RGB is a
// camera's, white-balanced by those factors; MERL publishes no colour
// characterisation, so the scaled values are taken as linear sRGB, as
// renderers do. RGL's "_rgb" materials are their spectra converted to linear
// sRGB by the database's authors. Both are therefore linear sRGB (D65) here.

#include "paintlab/measured_brdf/rgb_brdf.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace paintlab::measured {

class NeuralBrdf final : public RgbBrdf {
public:
    static constexpr std::size_t kInputs = 6;
    static constexpr std::size_t kHidden = 21;
    static constexpr std::size_t kOutputs = 3;

    // Row-major weights as stored (x W: W1 is kInputs x kHidden).
    NeuralBrdf(std::string name, std::vector<double> w1, std::vector<double> b1, std::vector<double> w2,
               std::vector<double> b2, std::vector<double> w3, std::vector<double> b3);

    const std::string& name() const override { return m_name; }
    RgbValue eval(const Direction& wi, const Direction& wo) const override;

private:
    std::string m_name;
    std::vector<double> m_w1, m_b1, m_w2, m_b2, m_w3, m_b3;
};

// Every material of the file, in the file's order (keys "MERL/<name>",
// "RGL/<name>"; "_about" and other keys starting with "_" are skipped).
// Throws InputError naming the file and the key and field for a file that
// cannot be read or parsed, a missing weight, a wrong size or a value that is
// not a finite number.
std::vector<NeuralBrdf> loadNeuralBrdfs(const std::filesystem::path& file);

}  // namespace paintlab::measured
