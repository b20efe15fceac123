#pragma once
// What a Monte Carlo path's direction changes so far make of it: its class by
// the last change (McSettings::histogram_classes), and within class Other the
// part that decides which estimator scores it (HistogramOtherParts): the
// histogram, the reverse walks, the delta-chain walks or the flake images.
// "Smooth": a pigment vertex, the Lambertian substrate or a continuum flake;
// "delta": a mirror reflection (explicit flake, internal interface, metal).

#include "mc_connection.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"

namespace paintlab::mc {

struct PathHistory {
    PathClass path_class = PathClass::Beam;  // what the last direction change was
    bool delta_chain = true;                 // no smooth vertex yet (HistogramOtherParts::delta_chains)
    bool first_smooth = false;               // the first direction change was a smooth vertex
    int beam_flake_layer = -1;               // layer of the beam's first reflection (class BeamFlake)
    bool prefix_flake = false;               // a pigment vertex right after that reflection, in its layer
    bool flake_then_top = false;             // the last changes: that reflection, then the top's internal one
    bool prefix_flake_top = false;           // a pigment vertex right after both, in the flake's layer
    // How the path ends (HistogramOtherParts::ends_pigment_flake and
    // ends_pigment_top_flake; the forward flake images): 1 the last change was
    // a pigment vertex in the tiled layer end_layer, on a path of part
    // delta_first (deltaFirstPrefixAt); 2 then the internal reflection at the
    // paint's top; 3 after 1, and 4 after 2, a reflection off a flake of
    // end_layer; 0 anything else.
    int end_state = 0;
    int end_layer = -1;

    // A smooth direction change (pigment, Lambertian substrate, continuum flake).
    void smoothChange();
    // A pigment scattering in `layer` (tiled_layer: it has a flake tile).
    void pigmentScatter(int layer, bool tiled_layer);
    // A delta direction change other than the beam's first flake reflection;
    // `at_top`: the internal reflection at the paint's top.
    void deltaChange(bool at_top);
    // A mirror reflection off an explicit flake of `layer`: the class after it.
    void flakeReflection(int layer);
    // Whether a pigment vertex in `layer` now leaves the path in part
    // delta_first of class Other (HistogramOtherParts): its prefix is none of
    // delta_chains, smooth_first, beam_flake_pigment and beam_flake_top_pigment,
    // which are fixed at the first smooth vertex.
    bool deltaFirstPrefixAt(int layer) const;
    // Whether the histogram scores this path's escape.
    bool histogramScores(const HistogramClasses& classes, const HistogramOtherParts& parts) const;
};

}  // namespace paintlab::mc
