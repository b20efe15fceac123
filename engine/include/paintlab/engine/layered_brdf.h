#pragma once
// The fast model's output: a tabulated spectral BRDF of a layered paint
// (shared/ARCHITECTURE.md, "The fast model"). Built by adding-doubling per
// wavelength band and azimuthal Fourier order; evaluated anywhere by
// interpolation in mu and summation of the Fourier series.
//
// The smooth top interface's mirror reflection is a delta, not part of
// eval(): renderers get it from specularReflectance() as a mirror term.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/recipe.h"

#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab {

// One point on the accuracy-vs-time curve of the fast model.
struct FastModelSettings {
    int nodes = 24;                       // quadrature nodes per hemisphere
    int orders = 16;                      // Fourier orders 0 .. orders-1
    int bands = 16;                       // wavelengths over 380-780 nm
    double max_start_tau = 1.0 / 1024.0;  // largest optical thickness of the starting sublayer
    int slices = 4;                       // slices per layer with a depth-varying concentration
    int flake_polar = 24;                 // flake-normal samples (polar x azimuth) for the flake kernels
    int flake_azimuth = 48;
};

enum class Preset { Preview, Standard, Reference };

// Throws InputError for an unknown name. Names: preview, standard, reference.
Preset presetFromName(std::string_view name);
std::string_view presetName(Preset preset);
FastModelSettings presetSettings(Preset preset);

// Called with the fraction done (0..1); return false to cancel.
using ProgressCallback = std::function<bool(double fraction)>;

class LayeredBrdf final : public SpectralBrdf {
public:
    std::span<const double> wavelengthsNm() const override { return m_wavelengths_nm; }
    // Diffuse (everything but the top interface's mirror term), 1/sr.
    void eval(const Direction& wi, const Direction& wo, std::span<double> out_per_sr) const override;
    using SpectralBrdf::eval;

    // Fresnel reflectance of the top interface at this incidence cosine, per band.
    std::vector<double> specularReflectance(double cos_theta) const;
    // Directional-hemispherical albedo for light from wi, mirror term included, per band.
    std::vector<double> albedo(const Direction& wi) const;
    // Albedo for uniform diffuse incidence (mirror term included), per band.
    std::vector<double> diffuseAlbedo() const;

    const FastModelSettings& settings() const { return m_settings; }
    double computeSeconds() const { return m_seconds; }

    // Tabulated data per band: the cosines (in the ambient medium) of the
    // nodes that reach it, and f^m(mu_out, mu_in) per order (1/sr).
    struct BandTable {
        std::vector<double> mu;          // ascending
        std::vector<Eigen::MatrixXd> f;  // f[m](i_out, j_in)
        Eigen::VectorXd specular;        // top-interface reflectance at mu
        Eigen::VectorXd albedo;          // directional-hemispherical, incl. specular
        Eigen::VectorXd flux_weight;     // of mu in the ambient medium (sum 1)
    };
    const std::vector<BandTable>& bands() const { return m_bands; }

private:
    friend LayeredBrdf computeLayeredBrdf(const Recipe&, const FastModelSettings&, const ProgressCallback&);
    std::vector<double> m_wavelengths_nm;
    std::vector<BandTable> m_bands;
    FastModelSettings m_settings;
    double m_ambient_index = 1.0;
    std::vector<double> m_top_index_per_band;
    double m_seconds = 0.0;
};

// Runs the fast model. The recipe must be valid (validateRecipe). Throws
// Error("cancelled") if progress returns false. Bands run in parallel (TBB).
LayeredBrdf computeLayeredBrdf(const Recipe& recipe, const FastModelSettings& settings,
                               const ProgressCallback& progress = {});

}  // namespace paintlab
