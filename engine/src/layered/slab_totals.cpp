#include "paintlab/engine/layered/slab_totals.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/layered/boundary.h"
#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/layered/quadrature.h"

#include <cmath>
#include <numbers>
#include <sstream>

namespace paintlab::layered {

namespace {

[[noreturn]] void reject(const std::string& field, double value, const std::string& allowed) {
    std::ostringstream text;
    text << value << " is not allowed: " << allowed;
    throw InputError("<argument>", field, text.str());
}

}  // namespace

void checkSlabParameters(const SlabParameters& p) {
    if (!(p.albedo >= 0.0 && p.albedo <= 1.0)) reject("albedo", p.albedo, "must be in [0, 1]");
    if (!(p.optical_thickness >= 0.0))
        reject("optical_thickness", p.optical_thickness, "must be >= 0 (inf allowed)");
    if (!(p.g > -1.0 && p.g < 1.0)) reject("g", p.g, "must be in (-1, 1)");
    if (!(p.n_slab >= 1.0 && std::isfinite(p.n_slab))) reject("n_slab", p.n_slab, "must be finite and >= 1");
    if (!(p.n_slide_top >= 1.0 && std::isfinite(p.n_slide_top)))
        reject("n_slide_top", p.n_slide_top, "must be finite and >= 1");
    if (!(p.n_slide_bottom >= 1.0 && std::isfinite(p.n_slide_bottom)))
        reject("n_slide_bottom", p.n_slide_bottom, "must be finite and >= 1");
    if (!(p.theta_deg >= 0.0 && p.theta_deg < 90.0)) reject("theta_deg", p.theta_deg, "must be in [0, 90)");
    if (p.quad_points < 4 || p.quad_points > 512) reject("quad_points", p.quad_points, "must be in [4, 512]");
}

SlabTotals slabTotals(const SlabParameters& p) {
    checkSlabParameters(p);
    // Collimated direction inside the slab (Snell from air).
    const double sin_air = std::sin(p.theta_deg * std::numbers::pi / 180.0);
    const double sin_in = sin_air / p.n_slab;
    const double mu0 = p.theta_deg == 0.0 ? 1.0 : std::sqrt(1.0 - sin_in * sin_in);
    const Quadrature q = makeQuadrature(p.quad_points, p.n_slab, mu0);

    // As many Legendre moments as nodes per hemisphere, delta-M scaled (Wiscombe 1977).
    const DeltaMPhase phase = henyeyGreensteinDeltaM(p.g, p.quad_points);
    const double albedo = phase.scaledAlbedo(p.albedo);
    const double tau = phase.scaledTau(p.albedo, p.optical_thickness);
    const PhaseMatrices h = phaseMatrices(q.mu, phase.chi, 0);
    DoublingOptions doubling;
    doubling.max_start_tau = p.max_start_tau;
    const LayerOperator slab = homogeneousSlab(q, h, albedo, tau, 0, doubling);

    const Eigen::VectorXd c_out = outsideFluxWeights(q, p.n_slab);
    // The two incident distributions the totals need: unit collimated flux at node mu_0,
    // and the diffuse flux of a uniform outside radiance (sum 1).
    Eigen::MatrixXd incident = Eigen::MatrixXd::Zero(q.size(), 2);
    incident(q.collimated, 0) = 1.0;
    incident.col(1) = c_out;

    const bool bare = p.n_slab == 1.0 && p.n_slide_top == 1.0 && p.n_slide_bottom == 1.0;
    Eigen::MatrixXd reflected;
    Eigen::MatrixXd transmitted;
    if (bare) {
        reflected = slab.R01 * incident;
        transmitted = slab.T01 * incident;
    } else {
        LayerOperator top = topBoundary(q, p.n_slab, p.n_slide_top);
        LayerOperator bottom = bottomBoundary(q, p.n_slab, p.n_slide_bottom);
        if (tau == 0.0) {
            // Nothing scatters or absorbs: the trapped directions receive no light, but their
            // total reflection at both faces would make (I - R10 R01) singular there (0/0).
            // Any value below 1 gives the same, exact, result; use 0.
            for (int k = 0; k < q.n_trapped; ++k) top.R10(k, k) = bottom.R01(k, k) = 0.0;
        }
        // The adding equations of layer_operator.h, keeping only what light from above needs
        // and using that the boundary operators are diagonal.
        const Eigen::VectorXd r_bottom = bottom.R01.diagonal();
        const Eigen::VectorXd t_bottom = bottom.T01.diagonal();
        const Eigen::VectorXd r_top_out = top.R01.diagonal();
        const Eigen::VectorXd t_top_in = top.T01.diagonal();
        const Eigen::VectorXd r_top_in = top.R10.diagonal();
        const Eigen::VectorXd t_top_out = top.T10.diagonal();
        const auto n = q.size();
        const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
        // Slab over the bottom boundary, incident from above.
        const Eigen::MatrixXd down = (I - slab.R10 * r_bottom.asDiagonal()).partialPivLu().solve(slab.T01);
        const Eigen::MatrixXd R_sb = slab.R01 + slab.T10 * (r_bottom.asDiagonal() * down);
        const Eigen::MatrixXd T_sb = t_bottom.asDiagonal() * down;
        // Top boundary over that, for the two incident vectors only.
        const Eigen::MatrixXd x =
            (I - r_top_in.asDiagonal() * R_sb).partialPivLu().solve(t_top_in.asDiagonal() * incident);
        reflected = r_top_out.asDiagonal() * incident + t_top_out.asDiagonal() * (R_sb * x);
        transmitted = T_sb * x;
    }
    SlabTotals t;
    t.UR1 = reflected.col(0).sum();
    t.UT1 = transmitted.col(0).sum();
    t.URU = reflected.col(1).sum();
    t.UTU = transmitted.col(1).sum();
    return t;
}

}  // namespace paintlab::layered
