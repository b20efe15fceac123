// Scattered samples of a measured BRDF, interpolated (scattered_brdf.h).

#include "paintlab/engine/measured/scattered_brdf.h"

#include "paintlab/engine/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::measured {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

bool aboveHorizon(const Direction& d) noexcept { return d.z > 0.0 && std::isfinite(d.x + d.y + d.z); }

Direction normalised(const Direction& d) noexcept {
    const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    return {d.x / n, d.y / n, d.z / n};
}

}  // namespace

HalfDifference halfDifference(const Direction& wi_in, const Direction& wo_in) noexcept {
    const Direction wi = normalised(wi_in);
    const Direction wo = normalised(wo_in);
    const Direction h = normalised({wi.x + wo.x, wi.y + wo.y, wi.z + wo.z});
    const double theta_h = std::acos(std::clamp(h.z, -1.0, 1.0));
    const double phi_h = std::atan2(h.y, h.x);
    // wi in the half vector's frame: rotate by -phi_h about z, then by -theta_h about y.
    const double cp = std::cos(phi_h);
    const double sp = std::sin(phi_h);
    const double x1 = cp * wi.x + sp * wi.y;
    const double y1 = -sp * wi.x + cp * wi.y;
    const double ct = std::cos(theta_h);
    const double st = std::sin(theta_h);
    const double x2 = ct * x1 - st * wi.z;
    const double z2 = st * x1 + ct * wi.z;
    HalfDifference hd;
    hd.theta_h = theta_h;
    hd.theta_d = std::acos(std::clamp(z2, -1.0, 1.0));
    // Reciprocity (phi_d + pi) and isotropy (-phi_d): fold to [0, pi/2].
    double phi_d = std::fmod(std::atan2(y1, x2), std::numbers::pi);
    if (phi_d < 0.0) phi_d += std::numbers::pi;
    hd.phi_d = phi_d > kHalfPi ? std::numbers::pi - phi_d : phi_d;
    return hd;
}

ScatteredBrdf::Point ScatteredBrdf::pointOf(const HalfDifference& hd) noexcept {
    const double sd = std::sin(hd.theta_d);
    return {hd.theta_h, sd * std::cos(hd.phi_d), sd * std::sin(hd.phi_d), std::cos(hd.theta_d)};
}

double ScatteredBrdf::distance2(const Point& a, const Point& b) noexcept {
    const double h = a.theta_h - b.theta_h;
    const double x = a.dx - b.dx;
    const double y = a.dy - b.dy;
    const double z = a.dz - b.dz;
    return h * h + x * x + y * y + z * z;
}

ScatteredBrdf::ScatteredBrdf(std::span<const ScatteredSample> samples, std::size_t channels,
                             const std::string& source, ScatteredBrdfSettings settings)
    : m_channels(channels), m_settings(settings) {
    if (samples.empty()) throw InputError(source, "samples", "a measured BRDF needs samples; there are none");
    if (channels == 0) throw InputError(source, "channels", "a measured BRDF needs at least one channel");
    m_settings.neighbours = std::max<std::size_t>(1, m_settings.neighbours);
    m_points.reserve(samples.size());
    m_values.reserve(samples.size() * channels);
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const ScatteredSample& s = samples[i];
        const std::string field = "samples[" + std::to_string(i) + "]";
        if (!aboveHorizon(s.wi) || !aboveHorizon(s.wo))
            throw InputError(source, field, "both directions must be above the horizon (theta below 90 deg)");
        if (s.values.size() != channels)
            throw InputError(source, field + ".values",
                             std::to_string(s.values.size()) + " values for " + std::to_string(channels) +
                                 " channels");
        for (std::size_t c = 0; c < channels; ++c)
            if (!std::isfinite(s.values[c]) || s.values[c] < 0.0)
                throw InputError(source, field + ".values[" + std::to_string(c) + "]",
                                 std::to_string(s.values[c]) + " is not a finite f >= 0 (1/sr)");
        m_points.push_back(pointOf(halfDifference(s.wi, s.wo)));
        m_values.insert(m_values.end(), s.values.begin(), s.values.end());
    }
}

void ScatteredBrdf::eval(const Direction& wi, const Direction& wo, std::span<double> out) const noexcept {
    std::fill(out.begin(), out.end(), 0.0);
    if (!aboveHorizon(wi) || !aboveHorizon(wo)) return;
    const Point q = pointOf(halfDifference(wi, wo));
    // The k nearest, kept sorted by distance (k is small: insertion).
    const std::size_t k = std::min(m_settings.neighbours, m_points.size());
    std::vector<std::pair<double, std::size_t>> best;
    best.reserve(k + 1);
    for (std::size_t i = 0; i < m_points.size(); ++i) {
        const double d2 = distance2(q, m_points[i]);
        if (best.size() == k && d2 >= best.back().first) continue;
        const auto at = std::upper_bound(best.begin(), best.end(), std::make_pair(d2, i));
        best.insert(at, {d2, i});
        if (best.size() > k) best.pop_back();
    }
    // A query on a sample returns it (the weight 1/d^2 would be infinite).
    constexpr double kSame2 = 1e-18;
    const std::size_t channels = std::min(out.size(), m_channels);
    if (best.front().first < kSame2) {
        const double* v = &m_values[best.front().second * m_channels];
        std::copy(v, v + channels, out.begin());
        return;
    }
    double weight_sum = 0.0;
    for (const auto& [d2, i] : best) {
        const double w = 1.0 / d2;
        weight_sum += w;
        const double* v = &m_values[i * m_channels];
        for (std::size_t c = 0; c < channels; ++c) out[c] += w * v[c];
    }
    for (std::size_t c = 0; c < channels; ++c) out[c] /= weight_sum;
}

double ScatteredBrdf::nearestDistance(const Direction& wi, const Direction& wo) const noexcept {
    if (!aboveHorizon(wi) || !aboveHorizon(wo)) return std::numeric_limits<double>::infinity();
    const Point q = pointOf(halfDifference(wi, wo));
    double best = std::numeric_limits<double>::infinity();
    for (const Point& p : m_points) best = std::min(best, distance2(q, p));
    return std::sqrt(best);
}

Density density(const ScatteredBrdf& brdf, std::span<const DirectionPair> queries,
                const DensityCriterion& criterion) {
    Density d;
    d.samples = brdf.size();
    std::size_t within = 0;
    for (const DirectionPair& q : queries)
        if (brdf.nearestDistance(q.wi, q.wo) <= criterion.radius_rad) ++within;
    d.covered = queries.empty() ? 0.0 : static_cast<double>(within) / static_cast<double>(queries.size());
    const auto percent = [](double f) { return std::to_string(static_cast<int>(std::lround(100.0 * f))); };
    const std::string radius_deg =
        std::to_string(static_cast<int>(std::lround(criterion.radius_rad * 180.0 / std::numbers::pi)));
    if (d.samples < criterion.min_samples) {
        d.reason = std::to_string(d.samples) + " samples; shading needs at least " +
                   std::to_string(criterion.min_samples);
    } else if (d.covered < criterion.min_covered) {
        d.reason = "a sample within " + radius_deg + " deg (half/difference angles) of " +
                   percent(d.covered) + " % of the geometries shown; shading needs " +
                   percent(criterion.min_covered) + " %";
    }
    d.dense = d.reason.empty();
    return d;
}

}  // namespace paintlab::measured
