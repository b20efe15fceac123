#include "paintlab/raymaps/environment_map.h"

#include "paintlab/engine/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>

namespace paintlab::raymaps {

namespace {

Rgb3 pixelAt(const std::vector<float>& rgb, std::size_t pixel) {
    return Eigen::Vector3f(rgb[3 * pixel], rgb[3 * pixel + 1], rgb[3 * pixel + 2]).cast<double>();
}

constexpr double kPi = std::numbers::pi;
constexpr int kMaxWidth = 16384;
constexpr int kMaxHeight = 8192;

std::size_t upperIndex(const std::vector<double>& cdf, std::size_t begin, std::size_t count, double x) {
    // First entry of cdf[begin + 1 .. begin + count] above x: the bin is one less.
    const auto first = cdf.begin() + static_cast<std::ptrdiff_t>(begin + 1);
    const auto last = first + static_cast<std::ptrdiff_t>(count);
    const auto it = std::upper_bound(first, last, x);
    return std::min(static_cast<std::size_t>(it - first), count - 1);
}

}  // namespace

EnvironmentMap EnvironmentMap::load(const Environment& spec) {
    if (spec.file.empty()) {
        EnvironmentMap sky = builtinSky();
        return fromPixels(sky.m_width, sky.m_height, std::move(sky.m_rgb), "built-in sky", spec.rotation_deg,
                          spec.intensity);
    }
    const std::string name = spec.file.string();
    auto input = OIIO::ImageInput::open(name);
    if (!input) throw InputError(name, "environment", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& image = input->spec();
    if (image.width <= 0 || image.height <= 0 || image.width > kMaxWidth || image.height > kMaxHeight)
        throw InputError(name, "environment",
                         "image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                             "; a lat-long environment must be at most " + std::to_string(kMaxWidth) + " x " +
                             std::to_string(kMaxHeight));
    if (image.nchannels != 1 && image.nchannels < 3)
        throw InputError(name, "environment",
                         "image has " + std::to_string(image.nchannels) +
                             " channels; expected RGB (or one grey channel)");
    const auto pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    const int channels = image.nchannels == 1 ? 1 : 3;
    std::vector<float> data(pixels * static_cast<std::size_t>(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        throw InputError(name, "environment", "cannot read pixels: " + input->geterror());
    input->close();
    std::vector<float> rgb(pixels * 3);
    for (std::size_t i = 0; i < pixels; ++i)
        for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = channels == 1 ? data[i] : data[3 * i + c];
    return fromPixels(image.width, image.height, std::move(rgb), name, spec.rotation_deg, spec.intensity);
}

EnvironmentMap EnvironmentMap::fromPixels(int width, int height, std::vector<float> rgb,
                                          const std::string& source, double rotation_deg, double intensity) {
    if (width <= 0 || height <= 0 ||
        rgb.size() != 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw InputError(source, "environment", "pixel data does not match the image size");
    // Lossy EXR compression (DWA, B44, PXR24) rings into small negative
    // values around bright pixels (Blender's CC0 studio lights: -0.004 in
    // maps of mean ~0.5). Those down to -1 % of the map's mean radiance are
    // set to 0 (a documented repair, counted in clampedNegatives()); NaN,
    // infinite or more negative pixels are errors naming the first.
    double sum_abs = 0.0;
    for (const float x : rgb)
        if (std::isfinite(x)) sum_abs += std::abs(static_cast<double>(x));
    const double tolerance = 1e-2 * sum_abs / static_cast<double>(rgb.size());
    std::size_t clamped = 0;
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        if (std::isfinite(rgb[i]) && rgb[i] >= 0.0F) continue;
        if (std::isfinite(rgb[i]) && -static_cast<double>(rgb[i]) <= tolerance) {
            rgb[i] = 0.0F;
            ++clamped;
            continue;
        }
        const std::size_t pixel = i / 3;
        const std::size_t w = static_cast<std::size_t>(width);
        throw InputError(source, "environment",
                         "pixel (" + std::to_string(pixel % w) + ", " + std::to_string(pixel / w) +
                             ") channel " + std::to_string(i % 3) + " is " +
                             (std::isnan(rgb[i])   ? "NaN"
                              : std::isinf(rgb[i]) ? "infinite"
                                                   : "negative beyond compression noise (1 % of the mean)") +
                             "; radiance must be finite and non-negative");
    }
    EnvironmentMap map;
    map.m_width = width;
    map.m_height = height;
    map.m_rgb = std::move(rgb);
    map.m_clamped_negatives = clamped;
    if (intensity != 1.0)
        for (float& x : map.m_rgb) x *= static_cast<float>(intensity);
    map.m_rotation_rad = rotation_deg * kPi / 180.0;
    map.buildDistribution();
    return map;
}

EnvironmentMap EnvironmentMap::builtinSky(int width) {
    const int height = width / 2;
    std::vector<float> rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    const Rgb3 zenith(0.25, 0.45, 0.95);
    const Rgb3 horizon(1.0, 1.0, 1.05);
    const Rgb3 ground(0.3, 0.28, 0.25);
    for (int v = 0; v < height; ++v) {
        const double theta = kPi * (v + 0.5) / height;
        const double cos_theta = std::cos(theta);
        // Above the horizon: horizon-to-zenith blend in sqrt(cos) (a sky is
        // bright over a thin band near the horizon); below: uniform ground.
        const Rgb3 c = cos_theta > 0.0 ? Rgb3(horizon + (zenith - horizon) * std::sqrt(cos_theta)) : ground;
        for (int u = 0; u < width; ++u)
            for (int k = 0; k < 3; ++k)
                rgb[3 * (static_cast<std::size_t>(v) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(u)) +
                    static_cast<std::size_t>(k)] = static_cast<float>(c[k]);
    }
    return fromPixels(width, height, std::move(rgb), "built-in sky");
}

void EnvironmentMap::buildDistribution(bool facing) {
    m_all = distribution(nullptr);
    m_facing.clear();
    for (int axis = 0; facing && axis < 6; ++axis) {
        Eigen::Vector3d a = Eigen::Vector3d::Zero();
        a[axis / 2] = axis % 2 == 0 ? 1.0 : -1.0;
        m_facing.push_back(distribution(&a));
    }
    const auto w = static_cast<std::size_t>(m_width);
    const auto h = static_cast<std::size_t>(m_height);
    const double pixel_solid_angle_per_sin =
        (2.0 * kPi / static_cast<double>(w)) * (kPi / static_cast<double>(h));
    m_luminance_integral = 0.0;
    for (std::size_t v = 0; v < h; ++v) {
        const double sin_theta = std::sin(kPi * (static_cast<double>(v) + 0.5) / static_cast<double>(h));
        for (std::size_t u = 0; u < w; ++u)
            m_luminance_integral +=
                luminance(pixelAt(m_rgb, v * w + u)) * sin_theta * pixel_solid_angle_per_sin;
    }
}

EnvironmentMap::Distribution EnvironmentMap::distribution(const Eigen::Vector3d* axis) const {
    const auto w = static_cast<std::size_t>(m_width);
    const auto h = static_cast<std::size_t>(m_height);
    Distribution d;
    d.pixel_weight.assign(w * h, 0.0);
    d.column_cdf.assign(h * (w + 1), 0.0);
    d.row_cdf.assign(h + 1, 0.0);
    // The facing distributions keep a floor of 0.1 below the axis's
    // horizon: a normal up to 55 degrees from its axis still sees some of it.
    constexpr double kBelowHorizon = 0.1;
    for (std::size_t v = 0; v < h; ++v) {
        const double sin_theta = std::sin(kPi * (static_cast<double>(v) + 0.5) / static_cast<double>(h));
        double row = 0.0;
        for (std::size_t u = 0; u < w; ++u) {
            const std::size_t i = v * w + u;
            // A black pixel still gets a little weight so that pdf() > 0
            // wherever radiance could be evaluated by bilinear filtering.
            double weight = (luminance(pixelAt(m_rgb, i)) + 1e-6) * sin_theta;
            if (axis != nullptr)
                weight *= std::max(0.0, axis->dot(uvToDirection(static_cast<double>(u) + 0.5,
                                                                static_cast<double>(v) + 0.5))) +
                          kBelowHorizon;
            d.pixel_weight[i] = weight;
            row += weight;
            d.column_cdf[v * (w + 1) + u + 1] = row;
        }
        d.row_cdf[v + 1] = d.row_cdf[v] + row;
    }
    d.weight_sum = d.row_cdf[h];
    return d;
}

const EnvironmentMap::Distribution& EnvironmentMap::facing(const Eigen::Vector3d& normal) const {
    if (m_facing.empty()) return m_all;
    Eigen::Index axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    return m_facing[static_cast<std::size_t>(2 * axis + (normal[axis] >= 0.0 ? 0 : 1))];
}

Eigen::Vector2d EnvironmentMap::directionToUv(const Eigen::Vector3d& d) const {
    const double theta = std::acos(std::clamp(d.y(), -1.0, 1.0));
    double phi = std::atan2(d.x(), -d.z()) - m_rotation_rad;
    phi -= 2.0 * kPi * std::floor(phi / (2.0 * kPi));
    return {phi / (2.0 * kPi) * m_width, theta / kPi * m_height};
}

Eigen::Vector3d EnvironmentMap::uvToDirection(double u, double v) const {
    const double phi = 2.0 * kPi * u / m_width + m_rotation_rad;
    const double theta = kPi * v / m_height;
    const double s = std::sin(theta);
    return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

Rgb3 EnvironmentMap::radiance(const Eigen::Vector3d& direction) const {
    const Eigen::Vector2d uv = directionToUv(direction.normalized());
    // Bilinear between pixel centres, wrapping in u, clamped in v.
    const double x = uv.x() - 0.5;
    const double y = std::clamp(uv.y() - 0.5, 0.0, m_height - 1.0);
    const double fx = x - std::floor(x);
    const double fy = y - std::floor(y);
    const int x0 = (static_cast<int>(std::floor(x)) % m_width + m_width) % m_width;
    const int x1 = (x0 + 1) % m_width;
    const int y0 = static_cast<int>(std::floor(y));
    const int y1 = std::min(y0 + 1, m_height - 1);
    const auto pixel = [&](int px, int py) {
        return pixelAt(m_rgb, static_cast<std::size_t>(py) * static_cast<std::size_t>(m_width) +
                                  static_cast<std::size_t>(px));
    };
    return (1 - fy) * ((1 - fx) * pixel(x0, y0) + fx * pixel(x1, y0)) +
           fy * ((1 - fx) * pixel(x0, y1) + fx * pixel(x1, y1));
}

EnvironmentMap::Sample EnvironmentMap::sample(double u1, double u2) const {
    return sampleFrom(m_all, u1, u2);
}

double EnvironmentMap::pdf(const Eigen::Vector3d& direction) const { return pdfOf(m_all, direction); }

EnvironmentMap::Sample EnvironmentMap::sampleFacing(const Eigen::Vector3d& normal, double u1,
                                                    double u2) const {
    return sampleFrom(facing(normal), u1, u2);
}

double EnvironmentMap::pdfFacing(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction) const {
    return pdfOf(facing(normal), direction);
}

EnvironmentMap::Sample EnvironmentMap::sampleFrom(const Distribution& d, double u1, double u2) const {
    const auto w = static_cast<std::size_t>(m_width);
    const auto h = static_cast<std::size_t>(m_height);
    const std::size_t v = upperIndex(d.row_cdf, 0, h, u1 * d.weight_sum);
    const double row_total = d.row_cdf[v + 1] - d.row_cdf[v];
    const std::size_t u = upperIndex(d.column_cdf, v * (w + 1), w, u2 * row_total);
    // Uniform within the pixel (in u, and in v: the pdf below accounts for sin theta).
    const double ru = (u1 * d.weight_sum - d.row_cdf[v]) / row_total;
    const double cu = d.column_cdf[v * (w + 1) + u];
    const double pixel_weight = d.pixel_weight[v * w + u];
    const double fu = std::clamp((u2 * row_total - cu) / pixel_weight, 0.0, 1.0);
    const double fv = std::clamp(ru, 0.0, 1.0);
    Sample s;
    s.direction = uvToDirection(static_cast<double>(u) + fu, static_cast<double>(v) + fv);
    s.radiance = radiance(s.direction);
    s.pdf_sr = pdfOf(d, s.direction);
    return s;
}

double EnvironmentMap::pdfOf(const Distribution& d, const Eigen::Vector3d& direction) const {
    const Eigen::Vector2d uv = directionToUv(direction.normalized());
    const auto u = static_cast<std::size_t>(std::clamp(uv.x(), 0.0, m_width - 1.0));
    const auto v = static_cast<std::size_t>(std::clamp(uv.y(), 0.0, m_height - 1.0));
    // Samples are uniform in (phi, theta) within a pixel, so the density per
    // solid angle divides by the sine at the direction itself.
    const double sin_theta = std::max(std::sin(kPi * uv.y() / m_height), 1e-12);
    const double p_pixel = d.pixel_weight[v * static_cast<std::size_t>(m_width) + u] / d.weight_sum;
    return p_pixel / ((2.0 * kPi / m_width) * (kPi / m_height) * sin_theta);
}

EnvironmentMap EnvironmentMap::withoutHotspots(int max_count, double threshold,
                                               std::vector<Hotspot>& hotspots) const {
    hotspots.clear();
    EnvironmentMap residual = *this;
    const auto w = static_cast<std::size_t>(m_width);
    const auto h = static_cast<std::size_t>(m_height);
    const double mean = m_luminance_integral / (4.0 * kPi);
    const std::size_t max_pixels = std::max<std::size_t>(1, w * h / 100);
    const auto lum = [&](std::size_t i) { return luminance(pixelAt(residual.m_rgb, i)); };
    const auto solidAngle = [&](std::size_t v) {
        return (2.0 * kPi / static_cast<double>(w)) * (kPi / static_cast<double>(h)) *
               std::sin(kPi * (static_cast<double>(v) + 0.5) / static_cast<double>(h));
    };
    std::vector<char> in_region(w * h, 0);
    for (int k = 0; k < max_count; ++k) {
        std::size_t peak = 0;
        for (std::size_t i = 1; i < w * h; ++i)
            if (lum(i) > lum(peak)) peak = i;
        const double peak_lum = lum(peak);
        if (!(peak_lum > threshold * mean) || !(mean > 0.0)) break;
        const double floor_lum = std::max(threshold * mean, 0.05 * peak_lum);
        // Flood fill from the peak (4-neighbours, wrapping in azimuth).
        std::vector<std::size_t> region;
        std::deque<std::size_t> queue{peak};
        in_region[peak] = 1;
        while (!queue.empty() && region.size() < max_pixels) {
            const std::size_t i = queue.front();
            queue.pop_front();
            region.push_back(i);
            const std::size_t u = i % w;
            const std::size_t v = i / w;
            const std::size_t next[4] = {v * w + (u + 1) % w, v * w + (u + w - 1) % w, v > 0 ? i - w : i,
                                         v + 1 < h ? i + w : i};
            for (const std::size_t n : next)
                if (in_region[n] == 0 && lum(n) > floor_lum) {
                    in_region[n] = 1;
                    queue.push_back(n);
                }
        }
        for (const std::size_t i : queue) in_region[i] = 0;  // not taken (size cap)
        // The surrounding sky: mean of the 4-neighbours outside the region.
        Rgb3 ring = Rgb3::Zero();
        int ring_count = 0;
        for (const std::size_t i : region) {
            const std::size_t u = i % w;
            const std::size_t v = i / w;
            const std::size_t next[4] = {v * w + (u + 1) % w, v * w + (u + w - 1) % w, v > 0 ? i - w : i,
                                         v + 1 < h ? i + w : i};
            for (const std::size_t n : next)
                if (in_region[n] == 0) {
                    ring += pixelAt(residual.m_rgb, n);
                    ++ring_count;
                }
        }
        if (ring_count > 0) ring /= ring_count;
        Hotspot spot{Eigen::Vector3d::Zero(), Rgb3::Zero(), 0.0};
        for (const std::size_t i : region) {
            const std::size_t u = i % w;
            const std::size_t v = i / w;
            const double omega = solidAngle(v);
            const Rgb3 excess = (pixelAt(residual.m_rgb, i) - ring).cwiseMax(0.0);
            spot.irradiance += excess * omega;
            spot.solid_angle_sr += omega;
            spot.direction +=
                luminance(excess) * omega *
                residual.uvToDirection(static_cast<double>(u) + 0.5, static_cast<double>(v) + 0.5);
            for (std::size_t c = 0; c < 3; ++c)
                residual.m_rgb[3 * i + c] = static_cast<float>(
                    static_cast<double>(residual.m_rgb[3 * i + c]) - excess[static_cast<Eigen::Index>(c)]);
        }
        if (!(spot.direction.norm() > 0.0)) break;
        spot.direction.normalize();
        hotspots.push_back(spot);
    }
    // The residual lights only the paint's moment rays, which sample it over
    // the sphere: no facing distributions (8 MB each for a 1024 x 512 map).
    residual.buildDistribution(false);
    return residual;
}

}  // namespace paintlab::raymaps
