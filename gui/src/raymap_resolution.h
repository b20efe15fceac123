#pragma once
// The ray map's resolution follows the view it is shown in (issue 27, item
// 5): when a scene's map is traced, its camera's width and height are set to
// fill the view's box (the view's device pixels, rounded down to a multiple
// of 64 so a small change of the window size finds the same cached map), its
// aspect ratio kept, within the precompute budget kMaxRayMapPixels. Qt-free.

#include <cstdint>

namespace paintlab::gui {

// At most 960 x 540 image pixels, 4x the demo scene's 480 x 270: the
// precompute's time grows with the pixels (docs/PERFORMANCE.md, "Ray maps":
// 5.3 s at 480 x 270 with the defaults on an idle 2-core machine), so tracing
// stays near 20 s there (longer under load: gui/README.md); the relight
// kernel of 960 x 540 takes ~5 ms.
inline constexpr std::int64_t kMaxRayMapPixels = std::int64_t{960} * 540;

struct PixelSize {
    int width = 0;
    int height = 0;
    bool operator==(const PixelSize&) const = default;
};

// The box a view of `view` device pixels asks for: each side rounded down to
// a multiple of 64, at least 128 x 64.
PixelSize rayMapBox(PixelSize view);

// The camera's resolution for a box: the largest of the camera's aspect
// ratio (width / height of `camera`) inside `box`, scaled down to at most
// kMaxRayMapPixels, each side at least 16.
PixelSize rayMapResolution(PixelSize box, PixelSize camera);

}  // namespace paintlab::gui
