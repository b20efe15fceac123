#pragma once
// The paper's split view of a match (issue 28, part 3): one sphere under a
// fixed set of lights, its left half shaded with the measured BRDF (the
// measurement's scattered samples interpolated, engine
// measured/scattered_brdf.h) and its right half with a recipe's fast-model
// BRDF, at the same exposure. Qt-free, so it can be checked without a
// display; the widget is split_sphere_view.h.
//
// Scene: an orthographic camera looking down -z (x right, y up), a unit
// sphere, three directional lights: a key light from the upper left, a
// dimmer fill from the right and a dim light from the camera standing in for
// an environment. Only f is shaded (a smooth top coat's mirror term is a
// delta that directional lights show at single points; it is left out on
// both halves). Isotropic BRDFs: each pixel's tangent frame is any one
// around its normal.

#include "paintlab/database/measurements.h"
#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/measured/scattered_brdf.h"
#include "paintlab/raymaps/relight.h"

#include <functional>
#include <span>
#include <vector>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

// A BRDF measurement's samples in linear sRGB (R, G, B order; D65 / 2°, as
// brdf_colour.h): RGB channels reordered, spectral values converted with the
// band weights of their wavelengths. Throws InputError naming the
// measurement and field for a multi-angle measurement, channels other than
// R, G and B, fewer than 2 wavelengths.
std::vector<measured::ScatteredSample> linearSrgbSamples(const db::Measurement& measurement);

struct SphereLight {
    Direction towards;  // unit vector to the light, camera frame
    double irradiance;  // W/m^2 on a surface facing it (a white diffuser facing the key light shows 0.8)
};
std::span<const SphereLight> splitSphereLights();

// The (wi, wo) pairs, in each pixel's tangent frame, that the measured
// (left) half of a size_px x size_px sphere asks the BRDF for: what
// measured::density() judges.
std::vector<measured::DirectionPair> splitSphereQueries(int size_px);

// f in linear sRGB (1/sr) for a direction pair in the tangent frame.
using RgbBrdf = std::function<Rgb(const Direction& wi, const Direction& wo)>;
RgbBrdf rgbBrdf(const measured::ScatteredBrdf& brdf);  // three channels, R, G, B
// The fast model as the render dock's explicit lights read it (raymaps
// RelightTables: linear sRGB, tabulated); the result keeps the tables.
RgbBrdf rgbBrdf(const LayeredBrdf& brdf);

// Linear sRGB radiance, row-major, top row first; 0 outside the sphere.
// Rows run in parallel; alive() is asked between rows and a false answer
// throws Error("cancelled"). Throws InputError if size_px is below 8.
raymaps::RgbImage renderSplitSphere(const RgbBrdf& left, const RgbBrdf& right, int size_px,
                                    const std::function<bool()>& alive = {});

// One exposure for both halves (EV for raymaps::toDisplayRgb8): the 99th
// percentile of the sphere's largest channel shown at 1, so a specular peak
// may clip but the body of both halves is in range.
double splitSphereExposureEv(const raymaps::RgbImage& image);

}  // namespace paintlab::gui
