#include "paintlab/engine/colour/ciede2000.h"

#include <cmath>
#include <numbers>

// Steps 1-3 below are those of Sharma, Wu & Dalal (2005), section "Implementation".

namespace paintlab {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double k25Pow7 = 6103515625.0;  // 25^7, exactly representable

double pow7(double x) noexcept {
    const double x2 = x * x;
    return x2 * x2 * x2 * x;
}

// Step 1: h' in degrees, [0, 360), and 0 for a' = b' = 0, where atan2 has no meaningful value.
double hueDeg(double b, double aPrime) noexcept {
    if (b == 0.0 && aPrime == 0.0) return 0.0;
    const double h = std::atan2(b, aPrime) / kDegToRad;
    return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

double ciede2000(const Lab& first, const Lab& second, double kL, double kC, double kH) noexcept {
    // Step 1: G rescales a* to lift the chroma of near-neutrals; then C' and h'.
    const double cBar = 0.5 * (std::hypot(first.a, first.b) + std::hypot(second.a, second.b));
    const double cBar7 = pow7(cBar);
    const double G = 0.5 * (1.0 - std::sqrt(cBar7 / (cBar7 + k25Pow7)));
    const double a1 = (1.0 + G) * first.a;
    const double a2 = (1.0 + G) * second.a;
    const double c1 = std::hypot(a1, first.b);
    const double c2 = std::hypot(a2, second.b);
    const double h1 = hueDeg(first.b, a1);
    const double h2 = hueDeg(second.b, a2);

    // Step 2. With a neutral among the two, hue is undefined: Delta h' = 0 and
    // (step 3) the mean hue is the sum, i.e. the other colour's hue.
    const double deltaL = second.L - first.L;
    const double deltaC = c2 - c1;
    const double chromaProduct = c1 * c2;
    double deltaH_deg = 0.0;
    if (chromaProduct != 0.0) {
        deltaH_deg = h2 - h1;
        if (deltaH_deg > 180.0)
            deltaH_deg -= 360.0;
        else if (deltaH_deg < -180.0)
            deltaH_deg += 360.0;
    }
    const double deltaH = 2.0 * std::sqrt(chromaProduct) * std::sin(0.5 * deltaH_deg * kDegToRad);

    // Step 3: means, with the mean hue taken the short way round the circle.
    const double lBar = 0.5 * (first.L + second.L);
    const double cBarPrime = 0.5 * (c1 + c2);
    double hBar = h1 + h2;
    if (chromaProduct != 0.0) {
        if (std::fabs(h1 - h2) <= 180.0)
            hBar *= 0.5;
        else
            hBar = hBar < 360.0 ? 0.5 * (hBar + 360.0) : 0.5 * (hBar - 360.0);
    }

    const double T =
        1.0 - 0.17 * std::cos((hBar - 30.0) * kDegToRad) + 0.24 * std::cos(2.0 * hBar * kDegToRad) +
        0.32 * std::cos((3.0 * hBar + 6.0) * kDegToRad) - 0.20 * std::cos((4.0 * hBar - 63.0) * kDegToRad);
    const double hRatio = (hBar - 275.0) / 25.0;
    const double deltaTheta_deg = 30.0 * std::exp(-hRatio * hRatio);
    const double cBarPrime7 = pow7(cBarPrime);
    const double rC = 2.0 * std::sqrt(cBarPrime7 / (cBarPrime7 + k25Pow7));
    const double lOffset2 = (lBar - 50.0) * (lBar - 50.0);
    const double sL = 1.0 + 0.015 * lOffset2 / std::sqrt(20.0 + lOffset2);
    const double sC = 1.0 + 0.045 * cBarPrime;
    const double sH = 1.0 + 0.015 * cBarPrime * T;
    const double rT = -std::sin(2.0 * deltaTheta_deg * kDegToRad) * rC;

    // The weighted distance, with the rotation term R_T for blues.
    const double termL = deltaL / (kL * sL);
    const double termC = deltaC / (kC * sC);
    const double termH = deltaH / (kH * sH);
    return std::sqrt(termL * termL + termC * termC + termH * termH + rT * termC * termH);
}

}  // namespace paintlab
