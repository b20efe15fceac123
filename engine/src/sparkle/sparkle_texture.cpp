// The sparkle texture's draws (sparkle_texture.h).

#include "paintlab/engine/sparkle/sparkle_texture.h"

#include "montecarlo/mc_random.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab {

namespace {

constexpr double kGammaAbove = 256.0;  // Poisson means above this are drawn as a gamma sum

std::uint64_t mixKey(std::uint64_t key, std::uint64_t value) {
    std::uint64_t state = key ^ (value * 0x9e3779b97f4a7c15ULL);
    return mc::splitMix64(state);
}

std::uint64_t signedBits(double cell) {
    const double c = std::isfinite(cell) ? std::clamp(cell, -9.0e15, 9.0e15) : 0.0;
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(c));
}

double standardNormal(mc::PathRng& rng) {
    // Box-Muller; 1 - u keeps the logarithm finite.
    const double u1 = 1.0 - rng.uniform();
    const double u2 = rng.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// Gamma(shape k >= 1, scale 1): Marsaglia and Tsang, ACM TOMS 26(3), 2000.
double gammaDraw(double k, mc::PathRng& rng) {
    const double d = k - 1.0 / 3.0;
    const double c = 1.0 / std::sqrt(9.0 * d);
    for (int tries = 0; tries < 1000; ++tries) {
        double x = 0.0;
        double v = 0.0;
        do {
            x = standardNormal(rng);
            v = 1.0 + c * x;
        } while (v <= 0.0);
        v = v * v * v;
        const double u = 1.0 - rng.uniform();
        if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
    }
    return k;  // never reached in practice (acceptance > 95 %)
}

// X - 1 for one term: the compound Poisson sum of glint weights over its mean.
double drawTerm(const SparkleTerm& term, mc::PathRng& rng) {
    const double lambda = term.mean_glints;
    if (!(lambda > 0.0)) return 0.0;
    if (lambda > kGammaAbove) {
        const double rel_var = term.relativeVariance();
        if (!(rel_var > 0.0)) return 0.0;
        const double shape = 1.0 / rel_var;
        // Shape < 1 cannot happen here (rel_var <= E[w^2]/E[w]^2 / 256 < 1 unless
        // the slice is > 500 free paths deep); Gamma(k < 1) = Gamma(k + 1) U^(1/k).
        const double x = shape >= 1.0
                             ? gammaDraw(shape, rng)
                             : gammaDraw(shape + 1.0, rng) * std::pow(1.0 - rng.uniform(), 1.0 / shape);
        return x * rel_var - 1.0;
    }
    // Poisson by inversion (sequential search; lambda <= 256 keeps exp(-lambda) > 1e-112).
    const double u = rng.uniform();
    double p = std::exp(-lambda);
    double cdf = p;
    int count = 0;
    while (u > cdf && count < 10000) {
        ++count;
        p *= lambda / count;
        cdf += p;
    }
    const double H = term.bottom_um - term.top_um;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) sum += std::exp(-term.sigma_e_per_um * H * rng.uniform());
    return sum / (lambda * term.mean_weight) - 1.0;
}

}  // namespace

std::uint64_t sparkleCellKey(double x_um, double y_um, double z_um, double element_side_um,
                             std::uint64_t seed) {
    const double side = element_side_um > 0.0 && std::isfinite(element_side_um)
                            ? std::exp2(std::floor(std::log2(element_side_um)))
                            : 1.0;
    std::uint64_t key = mixKey(seed, 0x737061726b6c65ULL);  // "sparkle"
    key = mixKey(key, signedBits(std::log2(side)));
    key = mixKey(key, signedBits(std::floor(x_um / side)));
    key = mixKey(key, signedBits(std::floor(y_um / side)));
    return mixKey(key, signedBits(std::floor(z_um / side)));
}

void drawSparkle(const SparkleStats& stats, std::uint64_t cell_key, std::span<double> modulation) {
    const std::size_t count = std::min(stats.terms.size(), modulation.size());
    for (std::size_t t = 0; t < count; ++t) {
        const SparkleTerm& term = stats.terms[t];
        // The window's bin: width a power of sqrt(2) near its angular diameter.
        const double level = std::round(2.0 * std::log2(std::max(term.window_width_rad, 1e-9)));
        const double width = std::exp2(0.5 * level);
        std::uint64_t key = mixKey(cell_key, static_cast<std::uint64_t>(term.layer));
        key = mixKey(key, static_cast<std::uint64_t>(term.component));
        key = mixKey(key, static_cast<std::uint64_t>(term.slice));
        key = mixKey(key, signedBits(level));
        key = mixKey(key, signedBits(std::floor(term.half_slope_x / width)));
        key = mixKey(key, signedBits(std::floor(term.half_slope_y / width)));
        mc::PathRng rng(key, 1, 2, 3);
        modulation[t] = drawTerm(term, rng);
    }
}

std::vector<double> sparkleBrdfModulation(const SparkleStats& stats, std::uint64_t cell_key) {
    std::vector<double> x(stats.terms.size(), 0.0);
    drawSparkle(stats, cell_key, x);
    std::vector<double> out(stats.flake_brdf_per_sr.size(), 0.0);
    for (std::size_t t = 0; t < x.size(); ++t)
        for (std::size_t b = 0; b < out.size() && b < stats.terms[t].flake_brdf_per_sr.size(); ++b)
            out[b] += stats.terms[t].flake_brdf_per_sr[b] * x[t];
    return out;
}

}  // namespace paintlab
