#pragma once
// Totals of a single raw-medium slab in air, with the definitions of Prahl's
// adding-doubling program (Prahl 1995; iad/ad documentation):
//   UR1, UT1: total reflected / transmitted flux for a collimated beam of unit flux
//             at theta in air, including the specular reflection and the unscattered beam;
//   URU, UTU: the same for diffuse (uniform radiance) incidence.
// The slab has single-scattering albedo a, optical thickness b (possibly +infinity),
// Henyey-Greenstein g, index n, and optional non-absorbing glass slides above and below.
//
// The refracted incidence direction is a node of the quadrature (quadrature.h), so
// the unscattered beam exp(-b/mu_0) and the specular terms are computed exactly.

#include <string>

namespace paintlab::layered {

struct SlabParameters {
    double albedo = 0.0;
    double optical_thickness = 0.0;  // may be +infinity
    double g = 0.0;
    double n_slab = 1.0;
    double n_slide_top = 1.0;     // 1 = no slide
    double n_slide_bottom = 1.0;  // 1 = no slide
    double theta_deg = 0.0;       // incidence angle in air, [0, 90)
    int quad_points = 32;         // nodes per hemisphere, >= 4
    // Largest optical thickness of the diamond starting layer (an accuracy knob: the
    // error falls as its square; see DoublingOptions in layer_operator.h).
    double max_start_tau = 1.0 / 4096.0;
};

struct SlabTotals {
    double UR1 = 0.0;
    double UT1 = 0.0;
    double URU = 0.0;
    double UTU = 0.0;
};

// Throws paintlab::InputError (source "<argument>", field = the member name) if a value
// is NaN or out of range: albedo in [0, 1], optical_thickness >= 0 (inf allowed),
// g in (-1, 1), n_slab and slide indices >= 1 and finite, theta_deg in [0, 90),
// quad_points in [4, 512], max_start_tau in [1e-12, 1].
void checkSlabParameters(const SlabParameters& p);

// Validates (see above, throws InputError), then computes the totals for Fourier order 0.
SlabTotals slabTotals(const SlabParameters& p);

}  // namespace paintlab::layered
