#include "mc_path_history.h"

namespace paintlab::mc {

void PathHistory::smoothChange() {
    if (path_class == PathClass::Beam) first_smooth = true;
    path_class = PathClass::Smooth;
    delta_chain = false;
    flake_then_top = false;
    end_state = 0;
}

void PathHistory::pigmentScatter(int layer, bool tiled_layer) {
    if (path_class == PathClass::BeamFlake && layer == beam_flake_layer) prefix_flake = true;
    if (flake_then_top && layer == beam_flake_layer) prefix_flake_top = true;
    const bool ends = tiled_layer && deltaFirstPrefixAt(layer);
    smoothChange();
    if (ends) {
        end_state = 1;
        end_layer = layer;
    }
}

void PathHistory::deltaChange(bool at_top) {
    flake_then_top = at_top && path_class == PathClass::BeamFlake;
    path_class = PathClass::Other;
    end_state = at_top && end_state == 1 ? 2 : 0;
}

void PathHistory::flakeReflection(int layer) {
    if (path_class == PathClass::Beam) {
        path_class = PathClass::BeamFlake;
        return;
    }
    const int next = layer == end_layer && (end_state == 1 || end_state == 2) ? end_state + 2 : 0;
    deltaChange(false);
    end_state = next;
}

bool PathHistory::deltaFirstPrefixAt(int layer) const {
    if (first_smooth || prefix_flake || prefix_flake_top || path_class == PathClass::Beam) return false;
    if (!delta_chain) return true;  // an earlier smooth vertex fixed the prefix
    // This vertex would be the first smooth one.
    return !((path_class == PathClass::BeamFlake || flake_then_top) && layer == beam_flake_layer);
}

bool PathHistory::histogramScores(const HistogramClasses& classes, const HistogramOtherParts& parts) const {
    switch (path_class) {
    case PathClass::Beam:
        return classes.beam;
    case PathClass::BeamFlake:
        return classes.beam_flake;
    case PathClass::Smooth:
        return classes.smooth;
    case PathClass::Other:
        break;
    }
    if (!classes.other) return false;
    if (delta_chain) return parts.delta_chains;
    if (first_smooth) return parts.smooth_first;
    if (prefix_flake) return parts.beam_flake_pigment;
    if (prefix_flake_top) return parts.beam_flake_top_pigment;
    if (end_state == 3) return parts.ends_pigment_flake;
    if (end_state == 4) return parts.ends_pigment_top_flake;
    return parts.delta_first;
}

}  // namespace paintlab::mc
