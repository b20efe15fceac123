#pragma once
// Fitting a recipe to measurements (issue 28): the inverse of the fast
// model. Given a template recipe, the fields to free (parameter_paths.h) with
// their bounds and measurements (observations.h), find the values that make
// the model look like the measurements, how sure they are, and what else
// would look the same.
//
// Loss: 0.5 sum r^2 over whitened residuals (each divided by its noise):
//   - multi-angle readings with spectra: (R_model - R_meas) / sigma_R per
//     wavelength, at the measured wavelengths that overlap the model's
//     (380-780 nm); ΔE00 per geometry reported;
//   - multi-angle readings with CIELAB only: (Lab_model - Lab_meas) / sigma_Lab;
//   - BRDF samples: [ln(1 + f cos θi) - ln(1 + f_meas cos θi)] / sigma_log per
//     channel, f the model's spectral BRDF (linear sRGB D65 of it for RGB
//     samples, brdf_colour.h), robust across the specular peak and the flop.
// Optimiser: the cost at the template's values and at `starts` - 1
// low-discrepancy (Halton, shifted by the seed) points inside the bounds; a
// Ceres search (bounded Levenberg-Marquardt, forward differences) at the
// search preset from the template and the best `searches` - 1 of them; the
// best distinct minima polished at the polish preset with central
// differences; the report (residuals, ΔE00, covariance) there.
// Uncertainty: Ceres' covariance at the optimum with the rank-revealing
// DENSE_SVD algorithm, scaled by the reduced chi-square when that exceeds 1
// (the model cannot reach the data: the noise alone understates the error).

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/fit/observations.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/recipe.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace paintlab::fit {

// A freed field and its bounds. Unset bounds: the declaration's allowed range
// (ParameterPath::min/max), except that a flake orientation spread starts at
// the narrowest one the fit's presets resolve (narrowestResolvedFlakeSpreadDeg,
// ~1.2° at standard). Bounds outside the allowed range, or lower >= upper,
// are an InputError naming the path.
struct FreeParameter {
    std::string path;
    std::optional<double> lower;
    std::optional<double> upper;
};

struct FitSettings {
    int starts = 16;         // the template, then Halton points shifted by the seed; >= 1
    std::uint64_t seed = 1;  // the same seed gives the same starts and result
    // Local searches: from the template and the starts with the lowest cost
    // (each start costs one evaluation; a search about ten Jacobians).
    int searches = 3;
    Preset search_preset = Preset::Preview;
    Preset polish_preset = Preset::Standard;  // also the report's preset
    int polish_count = 2;                     // best distinct search minima polished (those whose
                           // search cost is within 4x the best's + 10 x alternative_cost_abs)
    int search_iterations = 8;  // Ceres iterations per start
    int polish_iterations = 10;
    // Search on a log scale the parameters whose bounds are > 0 and span more
    // than a factor 10 (concentrations, thicknesses).
    bool log_scale = true;
    // Alternative minima: distinct polished minima with
    // cost <= best + max(alternative_cost_abs, alternative_cost_rel * best).
    // 2 in cost is 4 in chi-square: a two-sigma difference.
    double alternative_cost_abs = 2.0;
    double alternative_cost_rel = 0.25;
    // Identifiability: a pair with |correlation| above this is "not separately
    // determined"; a parameter whose 1 sigma exceeds its bound range (or lies
    // in the Jacobian's null space) is "not determined".
    double correlation_threshold = 0.95;
};

struct FitProblem {
    Recipe recipe;  // the template: must validate; freed fields start from its values
    std::vector<FreeParameter> free;
    Observations observations;
    FitSettings settings;
};

struct FitProgress {
    std::string stage;  // "search", "polish", "report"
    int start = 0;      // current start (search) or polished candidate
    int starts = 0;
    long evaluations = 0;  // model evaluations (one fast-model BRDF each)
    double best_cost = 0.0;
    double fraction = 0.0;  // 0..1, of the whole fit
};
// Return false to cancel: fitRecipe then throws FitCancelled.
using FitProgressCallback = std::function<bool(const FitProgress&)>;

class FitCancelled : public Error {
public:
    FitCancelled() : Error("cancelled") {}
};

struct FittedParameter {
    std::string path;
    std::string label;
    std::string unit;
    double initial = 0.0;  // the template's value
    double value = 0.0;
    double sigma = 0.0;  // 1 sigma; infinity where not determined
    double lower = 0.0;  // the bounds used
    double upper = 0.0;
    bool at_bound = false;
    bool determined = true;  // false: see FitResult::identifiability
};

enum class ObservationKind { MultiAngleSpectral, MultiAngleLab, BrdfSample };

// Residual of one observation (a multi-angle geometry or a BRDF sample).
struct ObservationResidual {
    std::size_t measurement = 0;  // index into Observations::multi_angle or ::brdf
    std::size_t index = 0;        // reading or sample within it
    ObservationKind kind = ObservationKind::MultiAngleSpectral;
    Side side = Side::Top;
    double whitened_rms = 0.0;  // RMS of its whitened residuals
    // BRDF: RMS over the channels of ln(1 + f cos θi) - ln(1 + f_meas cos θi)
    // (not whitened); 0 for multi-angle readings.
    double log_error = 0.0;
};

// Per multi-angle geometry: measured against fitted colour.
struct GeometryMatch {
    std::size_t measurement = 0;
    std::size_t index = 0;
    Side side = Side::Top;
    double illumination_deg = 45.0;
    double aspecular_deg = 0.0;
    Lab measured;  // the reading's Lab, or the Lab of its spectrum
    Lab fitted;
    double delta_e00 = 0.0;
    std::vector<double> wavelengths_nm;  // the fitted reflectance factors at these
    std::vector<double> fitted_reflectance_factor;
    double azimuth_deg = 0.0;  // out of the plane of incidence (observations.h)
};

enum class IdentifiabilityKind { Correlated, Undetermined, AtBound };

struct IdentifiabilityIssue {
    IdentifiabilityKind kind = IdentifiabilityKind::Undetermined;
    std::vector<std::string> paths;  // one (Undetermined, AtBound) or two (Correlated)
    double correlation = 0.0;        // Correlated only
    std::string message;  // "thickness_um of layers[1] and volume_fraction of ... are not separately
                          // determined: correlation 0.99"
};

struct AlternativeMinimum {
    Recipe recipe;
    double cost = 0.0;
    std::vector<double> values;  // per free parameter, FitResult::parameters' order
    double max_delta_e00 = 0.0;  // over the multi-angle geometries, against the measurement
};

struct FitResult {
    Recipe recipe;      // the template with the fitted values
    double cost = 0.0;  // 0.5 sum r^2 at the polish preset
    std::size_t residual_count = 0;
    double reduced_chi_square = 0.0;          // 2 cost / max(1, residuals - parameters)
    std::vector<FittedParameter> parameters;  // the problem's free order
    // Row-major, parameters.size()^2; NaN where a parameter is not determined.
    std::vector<double> correlation;
    std::vector<ObservationResidual> residuals;
    std::vector<GeometryMatch> geometries;
    std::vector<IdentifiabilityIssue> identifiability;
    std::vector<AlternativeMinimum> alternatives;  // best first, without the best
    std::vector<double> cost_history;              // best cost after each Ceres iteration, in order
    long evaluations = 0;                          // fast-model BRDFs computed
    double seconds = 0.0;
    double model_seconds = 0.0;  // of which in the fast model (computeLayeredBrdf + eval)
    double modelShare() const { return seconds > 0.0 ? model_seconds / seconds : 0.0; }
};

// The fast model's settings a fit runs at a preset: the preset's, with the
// starting sublayer of the doubling at most kFitMaxStartTau thick. The
// starting layer's error repeats with every doubling of a layer's optical
// thickness, a sawtooth of ~0.1 % in reflectance at the preview preset's
// 1/32: invisible in a picture, but a derivative sees it, and an opaque
// layer's thickness would look determined. At 1/256 it is ~1e-6 (tested)
// for about 1.3x the time of a preview BRDF.
inline constexpr double kFitMaxStartTau = 1.0 / 256.0;
FastModelSettings fitSettings(Preset preset);

// The bounds a free parameter gets when the user gives none: its allowed
// range (ParameterPath::min, max), except that a flake orientation spread
// starts at the narrowest spread both of the fit's presets resolve (~1.2 deg;
// below it the fast model is not converged, layered_brdf.h). The CLI's
// `fit --help` listing and the Match dock show these.
struct FitBounds {
    double lower = 0.0;
    double upper = 0.0;
};
FitBounds defaultFitBounds(const ParameterPath& parameter, const FitSettings& settings = {});

// Throws InputError naming the field for every bad input: a template that
// does not validate, a path that does not exist or is not numeric, bounds
// outside the allowed range, no observations, a NaN / infinite / negative
// value, noise <= 0 where given, wavelengths not ascending or not overlapping
// 380-780 nm, a bottom-side measurement on a substrate that is not
// transparent, a geometry below the horizon, settings out of range.
// Fields: "free[2].path", "multi_angle[0].readings[3].reflectance_factor[5]",
// "brdf[1].samples[7].values", "settings.starts".
void validateFitProblem(const FitProblem& problem);

// Runs the fit (validateFitProblem first). Throws FitCancelled if progress
// returns false (the problem, passed by value-semantics const&, is never
// changed); Error if no start could be evaluated.
FitResult fitRecipe(const FitProblem& problem, const FitProgressCallback& progress = {});

// The stack seen from below through its transparent substrate: the layers in
// reverse order with their depth profiles turned over, a clear layer of the
// substrate's index on top (the carrier) and air's index below as the new
// transparent medium. Throws InputError("substrate") if the substrate is not
// transparent.
Recipe recipeSeenFromBelow(const Recipe& recipe);

}  // namespace paintlab::fit
