#pragma once
// Angular quadrature of the fast model: n nodes per hemisphere in mu = cos(theta).
//
// Normalisation (Prahl 1995, quadrature): the weights integrate over mu in [0, 1],
// sum_i weight[i] = 1, so that the flux weights c_i = 2 mu_i weight[i] sum to one,
// sum_i 2 mu_i w_i = 2 int_0^1 mu dmu = 1. A radiance vector L_i therefore carries
// the flux F_i = c_i L_i in units of pi times the radiance (a uniform radiance 1
// carries flux 1).
//
// Where the medium's index exceeds the outside index (eta = n_medium / n_outside
// > 1), the interval is split at the critical cosine mu_c = sqrt(1 - 1/eta^2):
// Gauss-Legendre on [0, mu_c] (directions trapped by total internal reflection),
// and on [mu_c, 1] the escaping directions. The collimated incidence direction
// (its cosine inside the medium, mu_0) is always a node: Gauss-Radau with its
// fixed end at mu_0 on [mu_c, mu_0] and Gauss-Legendre on [mu_0, 1] (for normal
// incidence simply Radau on [mu_c, 1] with a node at mu = 1, Prahl's choice).
// The escape cone gets a share of the nodes proportional to the flux it carries,
// 1 - mu_c^2 = 1/eta^2 (at least 2, 3 for oblique incidence), rather than to its length
// as in Prahl's program: the outside world sees only these directions and the Fresnel
// reflectance varies fastest there. Every sub-interval integrates 2 mu exactly, so the
// escape cone carries exactly 1/eta^2.

#include <vector>

namespace paintlab::layered {

struct Quadrature {
    std::vector<double> mu;      // ascending, all in (0, 1]
    std::vector<double> weight;  // sum = 1 (integrates over mu in [0, 1])
    double mu_critical = 0.0;    // 0 when there is no total internal reflection
    int n_trapped = 0;           // nodes 0 .. n_trapped-1 lie below mu_critical
    int collimated = 0;          // index of the node at mu_0

    int size() const { return static_cast<int>(mu.size()); }
    // Flux weight c_i = 2 mu_i w_i (sum 1).
    double fluxWeight(int i) const;
};

// Gauss-Legendre rule with n >= 1 nodes on [a, b] (ascending), exact for degree 2n-1.
void gaussLegendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

// Gauss-Radau rule with n >= 2 nodes on [a, b] whose last node is b, exact for degree 2n-2.
void gaussRadauRight(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

// The split quadrature described above. n_nodes >= 4 per hemisphere; eta = n_medium / n_outside
// (>= 1 splits at the critical angle when > 1); mu_incident in (mu_c, 1] is the collimated
// direction inside the medium. Never throws for valid arguments (callers validate).
Quadrature makeQuadrature(int n_nodes, double eta, double mu_incident = 1.0);

}  // namespace paintlab::layered
