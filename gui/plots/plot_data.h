#pragma once
// The numbers behind the workstation's plots, computed from engine data alone
// (no Qt, no VTK), so each plot widget is a thin view and the data can be
// checked without a display.
//
// Speed (gui/README.md, "Plots"): a LayeredBrdf::eval costs a matrix-vector
// product per band and Fourier order, ~0.1 ms for the standard preset's 81
// bands, too slow for hundreds of directions on the GUI thread. The in-plane
// curves and the lobe grid instead take the azimuthal Fourier coefficients of
// all their polar angles in one LayeredBrdf::fourierCoefficientsGrid call and
// sum the series per direction: the same f as eval() (same tables, same
// interpolation, each band clipped at zero as eval() does), to rounding.
// Colours weight every direction's spectrum by the colours of the bands
// (colour/band_weights.h).

#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/measured/scattered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/engine/spectrum.h"

#include <span>
#include <string>
#include <vector>

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::gui {

// In-plane reflectance factor pi f for light at theta_i (azimuth 180°),
// viewed in the plane of incidence at view_deg: negative on the light's side
// (azimuth 180°), positive on the far side (azimuth 0°), so the mirror
// direction is at +theta_i. Linear sRGB channels (D65 / 2°) and CIE Y
// (D65 / 10°), as reflectanceFactorColour.
struct InplaneCurve {
    double theta_i_deg = 45.0;
    std::vector<double> view_deg;
    std::vector<double> r, g, b, y;
};

// Measured BRDF samples (linear sRGB, 1/sr) that lie in a plane of
// incidence, as points for the in-plane plot: reflectance factors pi f at
// view_deg in InplaneCurve's convention (negative on the light's side). A
// sample lies in the plane of the curve at theta_i_deg when its incidence is
// within tolerance_deg of it and its view direction within tolerance_deg of
// the plane through the normal and its light (its azimuth is free: the
// BRDF is taken as isotropic).
struct InplaneSamples {
    double theta_i_deg = 45.0;
    double tolerance_deg = 2.5;
    std::size_t total = 0;  // samples offered, in the plane or not
    std::vector<double> view_deg;
    std::vector<double> r, g, b;
};
InplaneSamples inplaneSamples(std::span<const measured::ScatteredSample> samples, double theta_i_deg,
                              double tolerance_deg = 2.5);

// -85 .. 85 degrees in 2.5 degree steps.
std::vector<double> inplaneViewAnglesDeg();
// One curve per incidence (each in [0, 90)). Throws InputError if an incidence is outside it.
std::vector<InplaneCurve> inplaneCurves(const LayeredBrdf& brdf, std::span<const double> incidences_deg);

// The BRDF over the outgoing hemisphere for one incidence: rings of constant
// theta_o (0 at the normal up to max_theta_deg) times azimuths (0 .. 360, the
// last not repeated). Index: ring * phi_count + azimuth.
struct LobeGrid {
    double theta_i_deg = 45.0;
    double phi_i_deg = 0.0;
    std::vector<double> theta_o_deg;  // per ring
    std::vector<double> phi_o_deg;    // per azimuth
    std::vector<double> y;            // luminance factor Y of pi f (D65 / 10°)
    std::vector<Rgb> linear_srgb;     // of pi f, D65 / 2°, unclipped
    double max_y = 0.0;
    double seconds = 0.0;  // wall time of lobeGrid()
};

// Throws InputError if theta_i_deg is outside [0, 90) or a count is below 2.
LobeGrid lobeGrid(const LayeredBrdf& brdf, double theta_i_deg, double phi_i_deg, int theta_count = 46,
                  int phi_count = 96, double max_theta_deg = 88.0);

// A spectrum with a name and the quantity it is of ("Reflectance factor (1)",
// "Absorption coefficient (1/µm)"): plots show one quantity at a time.
struct NamedSpectrum {
    std::string name;
    std::string quantity;
    Spectrum spectrum;
    friend bool operator==(const NamedSpectrum&, const NamedSpectrum&) = default;
};

// The paint's reflectance factor at each multi-angle geometry ("45as15"), in
// kAspecularAnglesDeg order.
std::vector<NamedSpectrum> multiAngleSpectra(const MultiAngleReport& report,
                                             std::span<const double> wavelengths_nm);
// "45as-15", "45as15", ...
std::string geometryName(double aspecular_deg);

// Every spectral field of the recipe's binders, components and substrate,
// named "<layer> > <component> > <label>" (the declarations' labels,
// parameters.h): the optical data of the ingredients the paint is made of.
// Fields that share an axis share a quantity ("Refractive index n (1)",
// "Absorption and scattering coefficients (1/µm)", "Reflectance and albedo
// (1)", ...), listed in that order: the colorants' coefficients first.
std::vector<NamedSpectrum> recipeSpectra(const Recipe& recipe);

// A display colour for a linear sRGB value: scaled so that its largest
// channel is 1 (hue and saturation, not brightness), clipped and encoded; 8 bits.
struct Rgb8 {
    unsigned char r = 0, g = 0, b = 0;
};
Rgb8 displayColour(const Rgb& linear_srgb);

}  // namespace paintlab::gui
