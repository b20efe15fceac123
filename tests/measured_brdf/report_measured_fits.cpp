// Report (label report, not in CI): fits a demo-structure recipe to each
// measured paint of shared/data/measured-brdf (issue 28, item 4, "Real
// measurements") and writes, for docs/VALIDATION.md,
//   measured_fits.csv     per paint: the template, the free parameters with
//                         their fitted values and sigma, the cosine-weighted
//                         log error over the ~2,000 samples (all, and outside
//                         5° of the mirror direction) of the fit, of ABC and of
//                         SGD, and ΔE00 at the six multi-angle geometries of
//                         each against the neural reconstruction;
//   measured_inplane.csv  Y of pi f in the plane of incidence at θi = 45° for
//                         the figure (tools/measured_brdf/plot_fits.py).
// The samples are the BRDF-sample contract's (sampler.h), the fit the
// engine's (fit.h). Output folder: $PAINTLAB_REPORT_DIR, else the working
// folder. $PAINTLAB_MEASURED_FIT_ONLY=<substring> fits only matching paints;
// $PAINTLAB_MEASURED_FIT_NOISE=default fits with the fitter's default BRDF
// noise instead of the relative one (measurementOf).

#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/measured_brdf/paints.h"
#include "paintlab/measured_brdf/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numbers>

namespace paintlab::measured {
namespace {

Recipe demoRecipe(const std::string& name) {
    return loadRecipeFile(std::string(PAINTLAB_DEMO_DIR) + "/recipes/" + name + ".json");
}

struct Template {
    std::string name;  // for the table
    Recipe recipe;
    std::vector<std::string> free;
};

// The silver metallic with the solid red's iron oxide added to its basecoat:
// a gold metallic as paint labs make one (aluminium flakes tinted by a
// transparent iron oxide), built from two demo structures.
Template goldTemplate() {
    Recipe recipe = demoRecipe("silver-metallic");
    const Recipe red = demoRecipe("solid-red");
    recipe.name = "Gold metallic (silver metallic + iron oxide)";
    recipe.layers[1].components.push_back(red.layers[1].components[0]);
    return {"silver-metallic + hematite",
            recipe,
            {"layers[1].components[0].volume_fraction", "layers[1].components[0].orientation_spread_deg",
             "layers[1].components[1].volume_fraction", "layers[1].components[1].hg_g",
             "layers[1].thickness_um", "substrate.albedo"}};
}

Template templateFor(const std::string& key) {
    const std::vector<std::string> solid{"layers[1].components[0].volume_fraction",
                                         "layers[1].components[0].hg_g", "layers[1].thickness_um",
                                         "layers[1].binder.absorption_per_um", "substrate.albedo"};
    const std::vector<std::string> metallic{"layers[1].components[0].volume_fraction",
                                            "layers[1].components[0].orientation_spread_deg",
                                            "layers[1].components[0].diameter_um",
                                            "layers[1].binder.absorption_per_um",
                                            "layers[1].thickness_um",
                                            "substrate.albedo"};
    const std::vector<std::string> pearl{"layers[1].components[0].volume_fraction",
                                         "layers[1].components[0].orientation_spread_deg",
                                         "layers[1].components[0].tio2_thickness_nm",
                                         "layers[1].components[0].mica_thickness_nm",
                                         "layers[1].components[1].volume_fraction",
                                         "layers[1].thickness_um",
                                         "substrate.albedo"};
    if (key.find("gold") != std::string::npos) return goldTemplate();
    if (key.find("silver") != std::string::npos || key.find("ilm_l3_37_metallic") != std::string::npos)
        return {"silver-metallic", demoRecipe("silver-metallic"), metallic};
    if (key.find("pearl") != std::string::npos || key.find("color-changing") != std::string::npos ||
        key.find("irid") != std::string::npos || key.find("blue-metallic") != std::string::npos)
        return {"pearlescent-two-layer", demoRecipe("pearlescent-two-layer"), pearl};
    return {"solid-red", demoRecipe("solid-red"), solid};
}

// relative_noise: each sample's noise on ln(1 + f cos θi) is that of a 5 %
// relative error of its mean channel x = f cos θi, 0.05 x / (1 + x), with a
// floor of 0.002 (a goniophotometer's stray-light floor); otherwise the
// fitter's default, 0.05 on the log residual, which is 5 % of 1/sr absolute
// where f cos θi << 1: for the diffuse part of every paint (f <= 0.3) that
// leaves the colour of a dark paint below the noise (docs/VALIDATION.md).
fit::BrdfMeasurement measurementOf(const RgbBrdf& brdf, const std::vector<SampleDirection>& directions,
                                   bool relative_noise) {
    fit::BrdfMeasurement m;
    m.name = brdf.name();
    m.values = fit::BrdfValues::LinearSrgb;
    for (const SampleDirection& d : directions) {
        const Direction wi = d.wi();
        const RgbValue f = brdf.eval(wi, d.wo());
        const double x = (f[0] + f[1] + f[2]) / 3.0 * wi.z;
        const double noise = relative_noise ? std::max(0.05 * x / (1.0 + x), 0.002) : 0.0;
        m.samples.push_back(
            {d.theta_i_deg, d.phi_i_deg, d.theta_o_deg, d.phi_o_deg, {f[0], f[1], f[2]}, noise});
    }
    return m;
}

// The samples farther than 5° from the mirror direction: outside the gloss
// lobe that a smooth clear coat cannot have (its mirror term is a delta).
std::vector<SampleDirection> offSpecular(const std::vector<SampleDirection>& all) {
    std::vector<SampleDirection> out;
    for (const SampleDirection& d : all) {
        const Direction wi = d.wi();
        const Direction wo = d.wo();
        if (-wi.x * wo.x - wi.y * wo.y + wi.z * wo.z < std::cos(5.0 * std::numbers::pi / 180.0))
            out.push_back(d);
    }
    return out;
}

void appendErrors(std::vector<std::string>& fields, const RgbBrdf* model, const MeasuredPaint& paint,
                  const std::vector<SampleDirection>& all, const std::vector<SampleDirection>& off) {
    if (model == nullptr) {
        fields.insert(fields.end(), 2 + kAspecularAnglesDeg.size(), "");
        return;
    }
    fields.push_back(io::csvNumber(cosineLogRms(*model, paint.neural, all)));
    fields.push_back(io::csvNumber(cosineLogRms(*model, paint.neural, off)));
    const std::array<Lab, 6> ref = multiAngleLabs(paint.neural);
    const std::array<Lab, 6> lab = multiAngleLabs(*model);
    for (std::size_t k = 0; k < lab.size(); ++k) fields.push_back(io::csvNumber(ciede2000(lab[k], ref[k])));
}

double luminance(const RgbValue& f) { return std::numbers::pi * linearSrgbToXyz({f[0], f[1], f[2]}).Y; }

TEST(MeasuredBrdfReport, FitEveryPaint) {
    const char* dir_env = std::getenv("PAINTLAB_REPORT_DIR");
    const std::filesystem::path out_dir = dir_env != nullptr ? dir_env : ".";
    const char* only_env = std::getenv("PAINTLAB_MEASURED_FIT_ONLY");
    const std::string only = only_env != nullptr ? only_env : "";
    const char* noise_env = std::getenv("PAINTLAB_MEASURED_FIT_NOISE");
    const bool relative_noise = noise_env == nullptr || std::string(noise_env) != "default";
    std::filesystem::create_directories(out_dir);

    std::vector<MeasuredPaint> paints = loadMeasuredPaints(PAINTLAB_MEASURED_BRDF_DIR);
    // One of each template first, so that an interrupted run has them.
    const std::vector<std::string> order{"dark-red",       "silver",         "pearl-paint",   "white-paint",
                                         "gold-metallic",  "color-changing", "blue-metallic", "phenolic",
                                         "two-layer-gold", "irid",           "ilm_l3",        "spectralon"};
    const auto rank = [&](const MeasuredPaint& p) {
        for (std::size_t k = 0; k < order.size(); ++k)
            if (p.neural.name().find(order[k]) != std::string::npos) return k;
        return order.size();
    };
    std::stable_sort(paints.begin(), paints.end(),
                     [&](const MeasuredPaint& a, const MeasuredPaint& b) { return rank(a) < rank(b); });
    const std::vector<SampleDirection> all = sampleDirections();
    // The fit sees all ~2,000 samples, the errors are over the same.
    const std::vector<SampleDirection>& fitted_directions = all;
    const std::vector<SampleDirection> off = offSpecular(all);

    std::string header = "paint,template,noise,free,cost,reduced_chi_square,evaluations,seconds";
    for (const char* model : {"fit", "abc", "sgd"}) {
        header += std::string(",") + model + "_log_error," + model + "_log_error_off_specular";
        for (double a : kAspecularAnglesDeg)
            header += std::string(",") + model + "_de00_45as" + io::formatNumber(a);
    }
    std::string table = header + "\n";
    std::string inplane = "paint,model,view_deg,Y\n";

    for (const MeasuredPaint& paint : paints) {
        if (!only.empty() && paint.neural.name().find(only) == std::string::npos) continue;
        Template t = templateFor(paint.neural.name());
        fit::FitProblem problem;
        problem.recipe = t.recipe;
        for (const std::string& path : t.free) problem.free.push_back({path, std::nullopt, std::nullopt});
        problem.observations.brdf.push_back(measurementOf(paint.neural, fitted_directions, relative_noise));
        // The fitter's default multi-start (FitSettings): what the CLI and
        // the Match dock run.
        problem.settings.seed = 28;
        const fit::FitResult result = fit::fitRecipe(problem, [&](const fit::FitProgress& p) {
            std::cerr << paint.neural.name() << " " << p.stage << " " << p.start << "/" << p.starts << " "
                      << p.evaluations << " evaluations, cost " << p.best_cost << "\n";
            return true;
        });

        const LayeredBrdf fitted_brdf = computeLayeredBrdf(result.recipe, presetSettings(Preset::Standard));
        const SpectralAsRgb fitted("fit", fitted_brdf);
        std::string free;
        for (const fit::FittedParameter& p : result.parameters) {
            if (!free.empty()) free += "; ";
            free += p.path + " = " + io::formatNumber(p.value) + " ± " +
                    (std::isfinite(p.sigma) ? io::formatNumber(p.sigma) : std::string("undetermined")) +
                    (p.at_bound ? " (at bound)" : "");
        }
        std::vector<std::string> fields{io::csvField(paint.neural.name()),
                                        io::csvField(t.name),
                                        relative_noise ? "relative" : "default",
                                        io::csvField(free),
                                        io::csvNumber(result.cost),
                                        io::csvNumber(result.reduced_chi_square),
                                        std::to_string(result.evaluations),
                                        io::csvNumber(result.seconds)};
        appendErrors(fields, &fitted, paint, all, off);
        appendErrors(fields, paint.abc ? &*paint.abc : nullptr, paint, all, off);
        appendErrors(fields, paint.sgd ? &*paint.sgd : nullptr, paint, all, off);
        table += io::csvJoin(fields);
        std::cout << paint.neural.name() << " (" << t.name << "): " << free << "\n  fit log error "
                  << fields[8] << ", " << result.seconds << " s, " << result.evaluations << " evaluations\n";

        const Direction wi = directionFromAnglesDeg(45.0, 0.0);
        for (int view = -80; view <= 80; ++view) {
            const Direction wo = directionFromAnglesDeg(std::abs(view), view < 0 ? 180.0 : 0.0);
            const auto row = [&](const char* model, const RgbBrdf& brdf) {
                inplane += io::csvJoin({io::csvField(paint.neural.name()), model, std::to_string(view),
                                        io::csvNumber(luminance(brdf.eval(wi, wo)))});
            };
            row("neural", paint.neural);
            row("fit", fitted);
            if (paint.abc) row("abc", *paint.abc);
            if (paint.sgd) row("sgd", *paint.sgd);
        }
        // Written after each paint, so that an interrupted run keeps what it did.
        io::writeFileAtomically(out_dir / "measured_fits.csv", table);
        io::writeFileAtomically(out_dir / "measured_inplane.csv", inplane);
    }
}

}  // namespace
}  // namespace paintlab::measured
