#pragma once
// The paint at one wavelength as the Monte Carlo walk sees it: homogeneous
// slices (top first) with their binder index, continuous medium and flake
// statistics, and the substrate; plus, per viewer direction, the closed-form
// specular "exit chain" used by next-event estimation.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/optics/flake_orientation.h"
#include "paintlab/engine/recipe.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <vector>

namespace paintlab::mc {

// Cosines of the full model's interference-flake R and T tables (evenly
// from 0 to 1, linear in between): a flake's fringes are a few periods over
// the whole range, so 256 intervals leave interpolation far below the
// Monte Carlo's statistical error.
inline constexpr int kFlakeTableCosines = 257;

struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;
};
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Orthonormal basis (b1, b2) around the unit vector n (Duff et al., JCGT 2017).
inline void orthonormalBasis(const Vec3& n, Vec3& b1, Vec3& b2) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    b1 = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    b2 = {b, sign + n.y * n.y * a, -n.y};
}

// The unit vector at polar cosine cos_theta and azimuth phi (from b1 of
// orthonormalBasis) about the unit vector `axis`.
inline Vec3 directionAround(const Vec3& axis, double cos_theta, double phi) {
    Vec3 b1;
    Vec3 b2;
    orthonormalBasis(axis, b1, b2);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double cx = sin_theta * std::cos(phi);
    const double cy = sin_theta * std::sin(phi);
    return {cx * b1.x + cy * b2.x + cos_theta * axis.x, cx * b1.y + cy * b2.y + cos_theta * axis.y,
            cx * b1.z + cy * b2.z + cos_theta * axis.z};
}

// One kind of flake in a slice: area density (one face per unit volume),
// orientation distribution and reflectance / transmittance at the local
// cosine, linearly interpolated in tables: kMirrorTableSize cosines for
// mirror flakes (their complex Fresnel is costly in the walk's inner loops),
// the interference flakes' (the thin-film average) as the caller asks.
struct FlakeKind {
    double area_density_per_um = 0.0;
    FlakeOrientation orientation{0.0};
    bool interference = false;
    bool has_metal_index = false;
    std::complex<double> metal_index;
    double reflectance_normal = 0.0;
    double binder_n = 1.5;
    std::vector<double> table_R;  // on cos = i / (size - 1)
    std::vector<double> table_T;
    std::vector<double> rate_table;  // A E_D[|v.n|] on |cos v| = i / (size - 1)
    // Interference flakes: the stratified normals over which chainExtinction
    // averages (1 - T)|v.n| (they depend on the orientation alone: drawn once).
    std::vector<FlakeNormal> normals;

    double R(double cos_local) const;
    double T(double cos_local) const;  // 0 for mirror flakes
    // A mirror flake's R from its Fresnel formula (what table_R holds).
    double exactR(double cos_local) const;
};

inline constexpr int kMirrorTableSize = 1025;

struct Slice {
    double top_um = 0.0;
    double bottom_um = 0.0;
    int layer = 0;
    double n = 1.5;
    double sigma_a_per_um = 0.0;
    double sigma_s_per_um = 0.0;
    std::vector<PhaseLobe> lobes;
    std::vector<FlakeKind> flakes;

    double thicknessUm() const { return bottom_um - top_um; }
    // Rate at which a ray with |cos theta| = abs_cos meets flakes of kind k: A E_D[|v.n|].
    double flakeRate(std::size_t k, double abs_cos) const;
    // Extinction of the unscattered beam: pigments plus flakes, what an
    // interference flake transmits going straight on: sum A E_D[(1 - T)|v.n|].
    double chainExtinction(double abs_cos) const;
    // Scattering kernel (per sr and µm) from propagation direction v into v_out:
    // pigments sigma_s sum w HG + flakes A R(|v.h|) D(h) / 4.
    double kernel(const Vec3& v, const Vec3& v_out) const;
};

// Operator: the flake-free bottom of the paint as one reflecting surface
// (mc_bottom.h): a smooth vertex like the Lambertian, with its own f.
enum class SubstrateKind { Lambertian, Black, Metal, Transparent, Operator };

class BottomOperator;

struct PaintStack {
    double wavelength_nm = 550.0;
    double ambient_n = 1.0;
    std::vector<Slice> slices;  // top first; layers of zero thickness are left out
    SubstrateKind substrate = SubstrateKind::Black;
    double lambert_albedo = 0.0;
    std::complex<double> metal_index{1.0, 0.0};
    double below_n = 1.0;                          // transparent substrate
    std::shared_ptr<const BottomOperator> bottom;  // SubstrateKind::Operator

    // Reflectance of the substrate for a downward ray with cosine mu in the last slice
    // (0 for Lambertian and black, which are not mirrors).
    double substrateMirrorReflectance(double mu) const;
};

// The flake kinds of a whole layer at one wavelength (mean concentration),
// mirror flakes first, then interference flakes, each in component order and
// only those present: the order of layerFlakeGeometries (flake_tile.h).
std::vector<FlakeKind> layerFlakeKinds(const Layer& layer, double wavelength_nm);

// Throws InputError if a layer's thickness is not positive. `same_recipe`:
// optionally the stack of the same recipe and slicing at another wavelength,
// whose flakes' collision-rate tables and stratified normals (which depend
// on the flakes' area density and orientation, not on the wavelength) are
// reused where they match; the result is the same as without it.
// `flake_table_cosines`: the cosines (0 to 1, evenly) at which interference
// flakes' R and T are tabulated, linear in between; fewer for a quick
// estimate (the effect planner's sparkle model), see kFlakeTableCosines.
PaintStack buildPaintStack(const Recipe& recipe, double wavelength_nm, int slices_per_profiled_layer,
                           const PaintStack* same_recipe = nullptr,
                           int flake_table_cosines = kFlakeTableCosines);

// Henyey-Greenstein phase function (1/sr) of the cosine between propagation directions.
double henyeyGreenstein(double g, double cos_theta);

// For one viewer direction wo (ambient), per slice: the direction in the
// slice that refracts into wo, and the factors that carry radiance emitted
// there into wo through every smooth interface, attenuation included, summed
// over the specular bounces (scalar adding along the one invariant
// s = n sin theta), times (n_ambient / n_slice)^2.
struct ExitChain {
    double sx = 0.0, sy = 0.0;       // n_ambient times wo's tangential components
    std::vector<double> mu;          // cosine in the slice (0: wo is unreachable from it)
    std::vector<double> extinction;  // chainExtinction(mu) per slice
    std::vector<double> up;          // upward ray at the slice's top -> wo, times (n0/n)^2
    std::vector<double> down;        // downward ray at the slice's bottom -> wo, times (n0/n)^2
    double lambert = 0.0;            // upward ray at the substrate -> wo, times (n0/n)^2

    Vec3 direction(const PaintStack& stack, std::size_t slice, bool upward) const;
};

ExitChain exitChain(const PaintStack& stack, const Direction& wo);

}  // namespace paintlab::mc
