#pragma once
// A relit image as the screen shows it: exposure, the extended Reinhard tone
// map and sRGB encoding, 8 bits per channel. writeImage's PNG output and the
// workstation's render dock share it, so the two always look the same.

#include "paintlab/raymaps/relight.h"

#include <cstdint>
#include <vector>

namespace paintlab::raymaps {

// 3 bytes per pixel (R, G, B), row-major, top row first: image x 2^exposure_ev,
// tone-mapped per channel (white point 4) and sRGB-encoded.
std::vector<std::uint8_t> toDisplayRgb8(const RgbImage& image, double exposure_ev = 0.0);

}  // namespace paintlab::raymaps
