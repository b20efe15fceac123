#pragma once
// The fit's model side: observations checked and prepared once (geometries
// as directions, wavelengths overlapped with the model's, noise resolved),
// then, for a recipe, the whitened residuals (fit.h, "Loss") and, on request,
// the per-observation details of the report. Private to the fitter.

#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/fit/fit.h"

#include <atomic>
#include <cstddef>
#include <vector>

namespace paintlab::fit {

struct PreparedReading {
    std::size_t measurement = 0;
    std::size_t index = 0;
    Side side = Side::Top;
    double illumination_deg = 45.0;
    double aspecular_deg = 0.0;
    double azimuth_deg = 0.0;
    Direction wi;
    Direction wo;
    ColourConditions conditions;
    bool spectral = false;
    std::vector<double> wavelengths_nm;  // spectral: the measured ones inside 380-780 nm
    std::vector<double> measured;        // spectral: reflectance factors there
    std::vector<double> sigma;           // per wavelength
    std::optional<Lab> lab;              // as given
    double lab_sigma = kDefaultLabNoise;
};

struct PreparedSample {
    std::size_t measurement = 0;
    std::size_t index = 0;
    Side side = Side::Top;
    bool rgb = true;
    Direction wi;
    Direction wo;
    double cos_i = 1.0;
    std::vector<double> wavelengths_nm;  // spectral: the measured ones inside 380-780 nm
    std::vector<double> measured_log;    // ln(1 + f_meas cos θi) per channel
    double sigma = kDefaultBrdfLogNoise;
};

struct PreparedObservations {
    std::vector<PreparedReading> readings;
    std::vector<PreparedSample> samples;
    bool top = false;  // some observation is on that side
    bool bottom = false;
    std::size_t residual_count = 0;
};

// Checks and prepares; throws InputError naming the field (validateFitProblem).
PreparedObservations prepareObservations(const Observations& observations, const Recipe& recipe);

// The model BRDFs of one recipe, per side the observations need.
struct SideBrdfs {
    std::optional<LayeredBrdf> top;
    std::optional<LayeredBrdf> bottom;
};

// Computes the BRDFs (fast model at settings). nullopt if the recipe does not
// validate (a trial outside the joint constraints, e.g. total volume > 1).
std::optional<SideBrdfs> modelBrdfs(const Recipe& recipe, const PreparedObservations& prepared,
                                    const FastModelSettings& settings);

// Whitened residuals (out.size() == prepared.residual_count). Never throws.
void whitenedResiduals(const SideBrdfs& brdfs, const PreparedObservations& prepared, std::span<double> out);

// The report's per-observation residuals and per-geometry colour matches.
void observationDetails(const SideBrdfs& brdfs, const PreparedObservations& prepared,
                        std::vector<ObservationResidual>& residuals, std::vector<GeometryMatch>& geometries);

// Model reflectance factors pi f at the reading's geometry, on the model's wavelengths.
std::vector<double> modelReflectanceFactor(const SpectralBrdf& brdf, const Direction& wi,
                                           const Direction& wo);
// Linear interpolation of (x, y) at the points at (ends held).
std::vector<double> interpolate(std::span<const double> x, std::span<const double> y,
                                std::span<const double> at);

}  // namespace paintlab::fit
