#pragma once
// Structural similarity (SSIM) of two grey images, for comparing the GUI
// tests' screenshots with their baselines: Wang, Bovik, Sheikh, Simoncelli,
// "Image quality assessment: from error visibility to structural
// similarity", IEEE TIP 13(4), 2004, eq. (13) with their constants
// K1 = 0.01, K2 = 0.03 for the dynamic range L = 255, computed on 8 x 8
// windows moved 4 pixels at a time (uniform weights instead of the paper's
// 11 x 11 Gaussian: screenshots are sharp-edged text and flat panels, where
// the window shape matters little) and averaged (their mean SSIM, eq. 17).
// Header-only and Qt-free so that it is itself tested against closed forms.

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace paintlab::test {

struct GreyImage {
    int width = 0;
    int height = 0;
    std::vector<double> value;  // row-major, 0..255
    double at(int x, int y) const {
        return value[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)];
    }
};

// Mean SSIM in [-1, 1] (1: identical). Throws std::invalid_argument if the
// sizes differ or an image is smaller than one window.
inline double meanSsim(const GreyImage& a, const GreyImage& b) {
    constexpr int kWindow = 8;
    constexpr int kStride = 4;
    constexpr double kC1 = (0.01 * 255.0) * (0.01 * 255.0);
    constexpr double kC2 = (0.03 * 255.0) * (0.03 * 255.0);
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("SSIM: images of different sizes");
    if (a.width < kWindow || a.height < kWindow)
        throw std::invalid_argument("SSIM: image smaller than a window");
    double sum = 0.0;
    int windows = 0;
    for (int y0 = 0; y0 + kWindow <= a.height; y0 += kStride) {
        for (int x0 = 0; x0 + kWindow <= a.width; x0 += kStride) {
            double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
            for (int y = y0; y < y0 + kWindow; ++y) {
                for (int x = x0; x < x0 + kWindow; ++x) {
                    const double va = a.at(x, y);
                    const double vb = b.at(x, y);
                    sa += va;
                    sb += vb;
                    saa += va * va;
                    sbb += vb * vb;
                    sab += va * vb;
                }
            }
            constexpr double n = kWindow * kWindow;
            const double mu_a = sa / n;
            const double mu_b = sb / n;
            // Unbiased (n - 1) variances, as in the paper's eq. (5)-(6).
            const double var_a = std::max(0.0, (saa - n * mu_a * mu_a) / (n - 1.0));
            const double var_b = std::max(0.0, (sbb - n * mu_b * mu_b) / (n - 1.0));
            const double cov = (sab - n * mu_a * mu_b) / (n - 1.0);
            sum += ((2.0 * mu_a * mu_b + kC1) * (2.0 * cov + kC2)) /
                   ((mu_a * mu_a + mu_b * mu_b + kC1) * (var_a + var_b + kC2));
            ++windows;
        }
    }
    return sum / windows;
}

}  // namespace paintlab::test
