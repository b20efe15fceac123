#pragma once
// The per-pixel noise of a progressive ray map's relit paint, estimated from
// the map itself (docs/RAYMAPS.md, "Progressive refinement"): the relight of
// the average of all N passes against that of the odd passes alone
// (ProgressiveRayMap::writeOddPasses). What the noise report measures with
// two maps of disjoint seeds, without tracing a second map: what the
// workstation's background refinement shows and stops on.

#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"

namespace paintlab::raymaps {

struct NoiseEstimate {
    int pixels = 0;                // paint pixels whose 8 neighbours are paint too
    Rgb3 relative = Rgb3::Zero();  // RMS per-pixel relative noise of the full map, per channel
    double worst() const { return relative.maxCoeff(); }
};

// `full`, `odd`: relight(write()'s map) and relight(writeOddPasses()'s map)
// with the same tables; `input`: the full map's records (which pixels are
// paint); `passes` N >= 2. Per channel, over the paint pixels whose 8
// neighbours are paint (no edge pixel, whose coverage differs per pass) and
// whose mean is above 1e-3 of the channel's mean over them:
// sqrt(mean ((full - odd) / full)^2) sqrt(n_o / n_e), n_o = ceil(N / 2),
// n_e = N - n_o (raymap.h). Throws InputError if the images do not match the
// input's size or N < 2.
NoiseEstimate estimateProgressiveNoise(const RelightInput& input, const RgbImage& full, const RgbImage& odd,
                                       int passes);

}  // namespace paintlab::raymaps
