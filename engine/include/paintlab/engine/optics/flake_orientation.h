#pragma once
// Distribution of flake normals around the surface normal (z axis).
//
// Definition. Flakes are two-sided, so a normal n and -n are the same flake
// and only the upper hemisphere (cos alpha = mu >= 0) is used. The normals
// follow a von Mises-Fisher (spherical Gaussian) distribution truncated to
// the upper hemisphere, azimuth uniform:
//
//     D(mu) = kappa exp(kappa (mu - 1)) / (2 pi (1 - exp(-kappa)))   [1/sr],
//     kappa = 1 / sigma^2 - 1 / (pi/2)^2,   sigma = spread in radians,
//
// normalised over the upper hemisphere. Why this form: for small sigma the
// tilt is a 2-D Gaussian of sigma per axis (how effect coatings describe
// flake alignment); the -1/(pi/2)^2 shift makes sigma = 90 deg exactly the
// uniform hemisphere; normalisation, inverse-CDF sampling and mean cosine are
// closed forms stable from 0.1 to 90 deg. Spread 0 is the exact delta.
//
// Never throws; the spread is clamped to [0, 90] degrees (NaN -> 0).

namespace paintlab {

struct FlakeNormal {
    double x = 0.0, y = 0.0, z = 1.0;  // unit vector in the surface frame, z >= 0
};

class FlakeOrientation {
public:
    explicit FlakeOrientation(double spread_deg);

    double spreadDeg() const { return m_spread_deg; }
    double kappa() const { return m_kappa; }  // +infinity for the delta
    bool isDelta() const { return m_delta; }  // spread 0: every flake horizontal

    // D per steradian at a normal with cos(alpha) = cos_alpha; a negative
    // cosine is the same two-sided flake, so D(|cos_alpha|). 0 everywhere for
    // the delta (it has no density).
    double pdf(double cos_alpha) const;

    // Density of mu = cos(alpha) on [0, 1]: 2 pi D(mu).
    double pdfMu(double mu) const;

    // Inverse-CDF sample: mu from u1 (u1 = 0 gives mu = 1), azimuth 2 pi u2.
    // Deterministic for given u1, u2 in [0, 1].
    FlakeNormal sample(double u1, double u2) const;

    // E[cos alpha] = 1 / (1 - exp(-kappa)) - 1 / kappa (1 for the delta,
    // 1/2 for the uniform hemisphere).
    double meanCos() const;

    // E_D[|w . n|] for a direction w with cos(theta_w) = cos_w: the projected
    // area per unit flake area seen along w, so the flake extinction is
    // sigma_t(w) = A * meanProjectedCos(cos_w) for a flake area density A.
    // Exactly |cos_w| for the delta and 1/2 for the uniform hemisphere.
    // Computed by Gauss-Legendre quadrature over mu, split at the kink mu =
    // sin(theta_w) (see flake_orientation.cpp); accurate to ~1e-11.
    double meanProjectedCos(double cos_w) const;

private:
    double m_spread_deg = 0.0;
    double m_kappa = 0.0;
    double m_norm = 1.0;  // kappa / (1 - exp(-kappa)), the density of mu at mu = 1
    bool m_delta = true;
};

}  // namespace paintlab
