#pragma once
// The paint's light moments of the environment alone, computed, not traced
// (docs/RAYMAPS.md, "Light moments"): a control variate for the moment rays.
//
// l^m_j = integral over cell j of L(w) cos(m phi) mu dw splits into the
// environment as if nothing occluded it, E (the residual after the K_env
// hotspots), and what the scene changes, L - E. The first is a fixed
// quadrature of E shared by every pixel (EnvironmentMoments: points placed
// by the map's importance sampling on a Hammersley set, each weighted
// E / (N p), so its error does not vary from pixel to pixel as noise does);
// the moment rays then estimate only L - E, which is zero for every ray that
// escapes. Under an HDR whose light comes from a small part of the sphere
// (an opening of a courtyard) uniform rays hit or miss it at random: the
// per-pixel noise of the moments was 20-30 % with 64 rays, and the
// difference is small wherever the paint sees the sky.

#include "sampling.h"

#include "paintlab/raymaps/environment_map.h"

#include <vector>

namespace paintlab::raymaps {

class EnvironmentMoments {
public:
    EnvironmentMoments(const EnvironmentMap& environment, int points);

    // Adds the environment's moments in `frame` (z the shading normal, x
    // along the view's azimuth) to moments[j * orders + m].
    void add(const Frame& frame, int cells, int orders, std::vector<Rgb3>& moments) const;

    int points() const { return static_cast<int>(m_direction.size()); }

private:
    std::vector<Vec3> m_direction;
    std::vector<Rgb3> m_weight;  // E / (N p): radiance x solid angle
};

}  // namespace paintlab::raymaps
