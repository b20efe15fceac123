#pragma once
// The HDR environment that lights a scene: a lat-long (equirectangular)
// radiance image, from a file (OpenEXR, Radiance .hdr, ... through
// OpenImageIO) or the built-in analytic sky, with importance sampling
// proportional to luminance x sin(theta) (Pharr, Jakob, Humphreys, PBR 3rd ed.
// 14.2.4), so the path tracer's noise does not depend on where the bright
// parts of the environment are.
//
// Directions are world space, +y up. Column u of the image is the azimuth
// phi = 2 pi (u + 0.5) / width measured from -z towards +x (after the
// environment's rotation about +y), row v the polar angle
// theta = pi (v + 0.5) / height from +y.
//
// Bad files: missing, unreadable, not an image, fewer than 3 channels (1 is
// read as grey), larger than 16384 x 8192, or any NaN, infinite or negative
// value give an InputError naming the file (and the first bad pixel).

#include "paintlab/raymaps/scene.h"

#include <Eigen/Core>

#include <filesystem>
#include <vector>

namespace paintlab::raymaps {

class EnvironmentMap {
public:
    // The file of `spec`, or the built-in sky if it names none; intensity
    // and rotation applied.
    static EnvironmentMap load(const Environment& spec);
    // A clear-sky dome: zenith blue to a bright horizon, a grey ground below
    // (no sun: scenes add one as a SunLight). Radiance ~1 W/(m^2 sr) at the horizon.
    static EnvironmentMap builtinSky(int width = 256);
    // From linear RGB pixels (row-major, top row = zenith); checks values:
    // NaN, infinite and negative pixels are InputErrors naming the first,
    // except negatives down to -1 % of the map's mean radiance (lossy EXR
    // compression's ringing), which are set to 0 and counted.
    static EnvironmentMap fromPixels(int width, int height, std::vector<float> rgb, const std::string& source,
                                     double rotation_deg = 0.0, double intensity = 1.0);

    int width() const { return m_width; }
    int height() const { return m_height; }
    // Pixel channels of the file that were small negatives set to 0.
    std::size_t clampedNegatives() const { return m_clamped_negatives; }

    // Radiance arriving from direction (towards the light), bilinear.
    Rgb3 radiance(const Eigen::Vector3d& direction) const;

    struct Sample {
        Eigen::Vector3d direction;  // towards the environment
        Rgb3 radiance;
        double pdf_sr = 0.0;  // per unit solid angle
    };
    // u1, u2 uniform in [0, 1).
    Sample sample(double u1, double u2) const;
    double pdf(const Eigen::Vector3d& direction) const;
    // For next-event estimation at a surface of this normal: one of six
    // distributions (the axis nearest the normal), luminance x sin(theta) x
    // (max(0, cos to the axis) + 0.1), so that the light below the surface,
    // which cannot reach it, does not take the samples. A floor under an HDR
    // whose brightest part is low on the horizon wasted most of them. The
    // residual of withoutHotspots() has none: there they are sample(), pdf().
    Sample sampleFacing(const Eigen::Vector3d& normal, double u1, double u2) const;
    double pdfFacing(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction) const;

    // A bright compact region taken out of the map (docs/RAYMAPS.md, K_env):
    // its radiance above the surrounding sky, as a directional light.
    struct Hotspot {
        Eigen::Vector3d direction;  // power-weighted centre, towards it
        Rgb3 irradiance;            // W/m^2 on a surface facing it
        double solid_angle_sr = 0.0;
    };
    // Up to max_count hotspots, brightest first: connected pixels whose
    // luminance exceeds both `threshold` x the map's mean luminance and 5 %
    // of the region's peak, at most 1 % of the pixels each. Each region's
    // pixels are lowered to the mean of the pixels around it, and what was
    // above that becomes the hotspot: residual + hotspots = this map.
    EnvironmentMap withoutHotspots(int max_count, double threshold, std::vector<Hotspot>& hotspots) const;

    // Total power-like measure: the integral of luminance over the sphere (for tests).
    double luminanceIntegral() const { return m_luminance_integral; }

private:
    // Piecewise-constant 2-D distribution over pixels: marginal CDF over rows
    // and conditional CDFs over columns (each m_width + 1 long).
    struct Distribution {
        std::vector<double> row_cdf;
        std::vector<double> column_cdf;
        std::vector<double> pixel_weight;  // unnormalised
        double weight_sum = 0.0;
    };
    void buildDistribution(bool facing = true);
    Distribution distribution(const Eigen::Vector3d* axis) const;
    Sample sampleFrom(const Distribution& d, double u1, double u2) const;
    double pdfOf(const Distribution& d, const Eigen::Vector3d& direction) const;
    const Distribution& facing(const Eigen::Vector3d& normal) const;
    Eigen::Vector2d directionToUv(const Eigen::Vector3d& d) const;  // continuous pixel coordinates
    Eigen::Vector3d uvToDirection(double u, double v) const;

    int m_width = 0;
    int m_height = 0;
    std::vector<float> m_rgb;
    double m_rotation_rad = 0.0;
    Distribution m_all;                  // luminance x sin(theta)
    std::vector<Distribution> m_facing;  // +x, -x, +y, -y, +z, -z
    double m_luminance_integral = 0.0;
    std::size_t m_clamped_negatives = 0;
};

// Rec.709 luminance of linear RGB.
inline double luminance(const Rgb3& c) { return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z(); }

}  // namespace paintlab::raymaps
