#include "paintlab/raymaps/noise_estimate.h"

#include "paintlab/engine/error.h"

#include <cmath>
#include <string>
#include <vector>

namespace paintlab::raymaps {

NoiseEstimate estimateProgressiveNoise(const RelightInput& input, const RgbImage& full, const RgbImage& odd,
                                       int passes) {
    const auto w = static_cast<std::size_t>(input.width());
    const auto h = static_cast<std::size_t>(input.height());
    if (passes < 2)
        throw InputError("<argument>", "passes", std::to_string(passes) + " is below 2: no odd/even split");
    if (full.rgb.size() != 3 * w * h || odd.rgb.size() != full.rgb.size())
        throw InputError("<argument>", "image", "the relit images are not the ray map's size");
    std::vector<char> paint(w * h, 0);
    for (std::size_t i = 0; i < input.paintPixels(); ++i) paint[input.pixel(i)] = 1;
    std::vector<std::size_t> inner;
    for (std::size_t y = 1; y + 1 < h; ++y)
        for (std::size_t x = 1; x + 1 < w; ++x) {
            bool all = true;
            for (std::size_t dy = 0; dy < 3; ++dy)
                for (std::size_t dx = 0; dx < 3; ++dx) all = all && paint[(y + dy - 1) * w + x + dx - 1] != 0;
            if (all) inner.push_back(y * w + x);
        }
    NoiseEstimate out;
    out.pixels = static_cast<int>(inner.size());
    if (inner.empty()) return out;
    const int n_odd = (passes + 1) / 2;
    const double scale = static_cast<double>(n_odd) / (passes - n_odd);
    for (std::size_t c = 0; c < 3; ++c) {
        double mean = 0.0;
        for (const std::size_t p : inner) mean += static_cast<double>(full.rgb[3 * p + c]);
        mean /= static_cast<double>(inner.size());
        double sum = 0.0;
        int counted = 0;
        for (const std::size_t p : inner) {
            const auto a = static_cast<double>(full.rgb[3 * p + c]);
            const auto b = static_cast<double>(odd.rgb[3 * p + c]);
            if (!(a > 1e-3 * mean)) continue;  // black in this channel: no relative noise to speak of
            sum += (a - b) * (a - b) / (a * a);
            ++counted;
        }
        out.relative[static_cast<Eigen::Index>(c)] = counted > 0 ? std::sqrt(sum / counted * scale) : 0.0;
    }
    return out;
}

}  // namespace paintlab::raymaps
