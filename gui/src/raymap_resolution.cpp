#include "raymap_resolution.h"

#include <algorithm>
#include <cmath>

namespace paintlab::gui {

PixelSize rayMapBox(PixelSize view) {
    const auto round_down = [](int pixels, int least) { return std::max(least, pixels / 64 * 64); };
    return {round_down(view.width, 128), round_down(view.height, 64)};
}

PixelSize rayMapResolution(PixelSize box, PixelSize camera) {
    const double aspect = camera.width > 0 && camera.height > 0
                              ? static_cast<double>(camera.width) / camera.height
                              : 16.0 / 9.0;
    double width = std::min(static_cast<double>(box.width), box.height * aspect);
    const double pixels = width * (width / aspect);
    if (pixels > static_cast<double>(kMaxRayMapPixels))
        width *= std::sqrt(static_cast<double>(kMaxRayMapPixels) / pixels);
    const int w = std::max(16, static_cast<int>(std::floor(width)));
    int h = std::max(16, static_cast<int>(std::lround(w / aspect)));
    if (static_cast<std::int64_t>(w) * h > kMaxRayMapPixels) --h;  // the rounding never passes the budget
    return {w, h};
}

}  // namespace paintlab::gui
