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
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab {

namespace fast {
class SingleScatteringCorrection;
}

// The most quadrature nodes per hemisphere computeLayeredBrdf takes.
inline constexpr int kMaxNodes = 96;

// One point on the accuracy-vs-time curve of the fast model.
struct FastModelSettings {
    int nodes = 24;                       // quadrature nodes per hemisphere, at most kMaxNodes
    int orders = 16;                      // Fourier orders 0 .. orders-1
    int bands = 16;                       // wavelengths computed, evenly over 380-780 nm
    double max_start_tau = 1.0 / 1024.0;  // largest optical thickness of the starting sublayer
    int slices = 4;                       // slices per layer with a depth-varying concentration
    int flake_polar = 12;  // Gauss nodes (tilt x azimuth, per smooth piece) for the flake totals
    int flake_azimuth = 12;
    int flake_table = 129;  // cosines at which the flakes' reflectance is tabulated (cubic in between)
    // Azimuth points per orientation spread in the flake kernel's Fourier
    // coefficients (midpoint rule, at least orders + 8): 4 resolves the lobe.
    double flake_kernel_points_per_spread = 4.0;
    // Orders whose kernels fall below this (relative to order 0) are not
    // computed, unless the substrate reflects in that order (a mirror).
    double order_tolerance = 1e-6;
    // When larger than `bands`: the tables are interpolated (cubic in
    // wavelength) to this many bands, which wavelengthsNm() reports. Paint
    // spectra are smooth, but colour from a linearly interpolated coarse
    // spectrum is not accurate.
    int output_bands = 0;
    // The pigments' once-scattered light with their full phase function at the
    // exact directions (fast_model/single_scattering.h), the truncated one the
    // tables hold taken away: without it a sharp lobe (g >= 0.75) is wrong by
    // tens of percent away from its peak. Off only to measure what it does.
    bool exact_single_scattering = true;
    // A sharp phase function needs a finer angular grid for its multiple
    // scattering: if any pigment's delta-M truncation at `nodes` moments
    // (f = chi_nodes, the share of its scattering moved into the forward
    // peak) exceeds sharp_truncation, nodes, orders and the starting layer
    // become at least these (sharp_nodes 0: never). settings() reports what ran.
    double sharp_truncation = 1e-3;
    int sharp_nodes = 0;
    int sharp_orders = 0;
    double sharp_max_start_tau = 1.0;
    // Flakes of a narrow orientation spread reflect into a lobe about twice
    // as wide, which the angular grid must resolve: nodes and orders become
    // at least these divided by the narrowest flake spread in degrees
    // (capped at kMaxNodes; 0: never). settings() reports what ran.
    double flake_nodes_times_spread_deg = 0.0;
    double flake_orders_times_spread_deg = 0.0;
    // At most this many nodes and orders for narrow flakes (a search that
    // only ranks candidates can take the capped grid's error for its speed).
    int flake_max_nodes = kMaxNodes;
    int flake_max_orders = 2 * kMaxNodes;
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
    // Diffuse (everything but the top interface's mirror term), 1/sr: the
    // tables' Fourier series plus the exact single-scattering correction.
    void eval(const Direction& wi, const Direction& wo, std::span<double> out_per_sr) const override;
    using SpectralBrdf::eval;

    // Fresnel reflectance of the top interface at this incidence cosine, per band.
    std::vector<double> specularReflectance(double cos_theta) const;

    // The azimuthal Fourier series of eval() between two polar directions
    // (cosines in the ambient medium): f(wi, wo) = sum over m < orders() of
    // out[m * bands + b] cos(m (phi_o - phi_i)), per band b, 1/sr; what a
    // renderer's tables need. Not clipped at zero, unlike eval()
    // (clippedFourierSum, fast_model/fourier_series.h, sums it as eval() does).
    // The single-scattering correction is in it up to orders(): a lobe
    // sharper than that many orders is eval()'s alone.
    void fourierCoefficients(double cos_o, double cos_i, std::span<double> out) const;
    // fourierCoefficients() on a grid of direction pairs, reduced over the
    // bands by `weights` (bands() x C, e.g. band -> linear sRGB):
    // out[((o * cos_i.size() + i) * orders() + m) * C + c] =
    //   sum_b weights(b, c) f^m_b(cos_o[o], cos_i[i]). Each interpolation
    // basis is computed once, so it is much faster than pair by pair.
    // Throws InputError if the sizes do not fit.
    void fourierCoefficientsGrid(std::span<const double> cos_o, std::span<const double> cos_i,
                                 const Eigen::MatrixXd& weights, std::span<double> out) const;
    // Orders in fourierCoefficients(): the largest computed in any band.
    int orders() const;
    // Directional-hemispherical albedo for light from wi, mirror term included,
    // per band; from the tables (the single-scattering correction moves light
    // between directions and changes it by far less than the tables' error).
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
        // Interpolation (eval, albedo): f^m is smooth in the polar angle
        // theta_ref in the stack's densest medium (index reference_index), so
        // within each quadrature interval it is the polynomial through the
        // interval's nodes in theta_ref (barycentric form). Nodes
        // [piece_begin[p], piece_begin[p+1]) form interval p, whose lower end
        // is piece_mu_low[p]. The interval at the normal is mirrored to
        // negative angles by the parity of f^m, which avoids Runge's
        // phenomenon there.
        double reference_index = 1.0;
        std::vector<double> node_angle;   // theta_ref of each node (rad)
        std::vector<double> node_bary;    // barycentric weights within its (extended) piece
        std::vector<double> mirror_bary;  // weights of the mirrored nodes -theta (0: none)
        std::vector<int> piece_begin;     // pieces + 1 entries
        std::vector<double> piece_mu_low;
    };
    const std::vector<BandTable>& bands() const { return m_bands; }

    // The wavelengths, grid, interpolation and mirror term of `grid` with
    // each band's f^m and albedo from `tables` (same node counts: InputError
    // otherwise): how the full model's tables (montecarlo/mc_table.h) become
    // a LayeredBrdf that every tool takes. Their tables are complete: no
    // single-scattering correction is added to them.
    static LayeredBrdf withTables(const LayeredBrdf& grid, std::vector<BandTable> tables, double seconds);

private:
    friend LayeredBrdf computeLayeredBrdf(const Recipe&, const FastModelSettings&, const ProgressCallback&);
    std::vector<double> m_wavelengths_nm;
    std::vector<BandTable> m_bands;
    FastModelSettings m_settings;
    double m_ambient_index = 1.0;
    std::vector<double> m_top_index_per_band;
    // Per band (empty: none); shared, since copies of a LayeredBrdf are common.
    std::shared_ptr<const std::vector<fast::SingleScatteringCorrection>> m_single_scattering;
    double m_seconds = 0.0;
};

// The narrowest flake orientation spread (degrees, > 0) that these settings
// resolve with at most kMaxNodes nodes (flake_*_times_spread_deg); 0 when
// they do not follow the spread. Narrower flakes (but aligned ones, 0) run
// on the capped grid and are not converged.
double narrowestResolvedFlakeSpreadDeg(const FastModelSettings& settings);

// Runs the fast model. The recipe must be valid (validateRecipe). Throws
// Error("cancelled") if progress returns false. The slab kernels of the bands,
// then the (band, Fourier order) pairs run in parallel (TBB).
LayeredBrdf computeLayeredBrdf(const Recipe& recipe, const FastModelSettings& settings,
                               const ProgressCallback& progress = {});

}  // namespace paintlab
