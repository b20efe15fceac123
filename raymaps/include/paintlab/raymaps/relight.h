#pragma once
// Relight (docs/RAYMAPS.md, "Relight"): the paint of a ray map re-shaded
// with a LayeredBrdf. Per recipe: tables whose cost does not depend on the
// image (RelightTables); per image: one pass over the paint records,
// composited over the baked radiance (relight).

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/raymaps/raymap.h"

#include <filesystem>
#include <vector>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::raymaps {

class RelightInput;

struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // linear sRGB radiance, row-major, top row first
};

// The BRDF reduced to linear sRGB (the weights that map a reflectance
// spectrum to linear sRGB under D65, white -> (1, 1, 1)) and tabulated on
// fixed grids: f_rgb(mu_o, mu_i, dphi) for the explicit lights, the cell
// averages of its Fourier coefficients f^m(mu_o, j) for the light moments,
// and the clear coat's mirror reflectance R(mu_o).
class RelightTables {
public:
    // cells, orders: the ray map's J and M_L. Throws InputError if out of range.
    RelightTables(const LayeredBrdf& brdf, int cells, int orders);

    static constexpr int kMuNodes = 33;  // mu = cos(pi / 2 k / (kMuNodes - 1))
    // dphi = pi k / (kPhiNodes - 1): even in dphi, f is a cosine series whose
    // order-m term turns m times faster than dphi itself, so the grid is
    // uniform in the angle (uniform in cos dphi it would be too coarse
    // near 0 and pi).
    static constexpr int kPhiNodes = 65;

    int cells() const { return m_cells; }
    int orders() const { return m_orders; }
    double seconds() const { return m_seconds; }
    // The BRDF (1/sr, RGB) at a direction pair through the light table, for tests.
    Rgb3 lightTable(double mu_o, double mu_i, double cos_dphi) const;
    // The clear coat's mirror reflectance (RGB) at this cosine (as the kernel: nearest fine node).
    Rgb3 coat(double mu_o) const;
    // Linear sRGB of a spectrum at the BRDF's wavelengths.
    Rgb3 toRgb(const std::vector<double>& spectrum) const;

    // [((o * kMuNodes + i) * kPhiNodes + p) * 4 + channel], channel 3 is 0:
    // one node is one 16-byte load in the kernel.
    const std::vector<float>& light() const { return m_light; }
    // The kernel reads the moment and coat tables without interpolating:
    // they are resampled (linearly, from the 33 theta_o nodes) on this many
    // nodes uniform in theta_o and read at the nearest (0.18 degrees away at most).
    static constexpr int kFineNodes = 257;
    // [((o * 3 + channel) * orders + m) * cells + j], o on the fine grid (the
    // kernel runs over j innermost); orders m >= 1 are divided by 127 (the
    // records' byte scale).
    const std::vector<float>& moments() const { return m_moments; }
    // [o * 3 + channel], o on the fine grid
    const std::vector<float>& coat() const { return m_coat; }

private:
    int m_cells;
    int m_orders;
    double m_seconds = 0.0;
    BandColourWeights m_weights;  // linear sRGB per band
    std::vector<float> m_light;
    std::vector<float> m_moments;
    std::vector<float> m_coat;
};

// Throws InputError naming the map's file if the map's cells or orders differ
// from the tables', or a band is corrupt. Decodes the map (RelightInput)
// each call: an interactive client keeps a RelightInput and calls the
// overload below per recipe change.
RgbImage relight(const RayMap& map, const RelightTables& tables);
// The kernel alone: one branch-free pass over the decoded paint pixels (TBB
// over rows), composited over the baked radiance. Throws InputError if the
// input's cells or orders differ from the tables'.
RgbImage relight(const RelightInput& input, const RelightTables& tables);

// Writes `image` x 2^exposure_ev: .exr as linear float RGB, .png as 8-bit
// sRGB after an extended Reinhard tone map (white point 4). Throws InputError
// for another extension, Error if the file cannot be written.
void writeImage(const RgbImage& image, const std::filesystem::path& path, double exposure_ev = 0.0);

}  // namespace paintlab::raymaps
