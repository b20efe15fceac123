// The fitter's parameter paths and its bad-input contract (issue 28, part 4
// "Bad input"): every bad input is an InputError naming the field.

#include "fit_test_util.h"

#include "paintlab/engine/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace paintlab {
namespace {

using fit::FitProblem;

// A small valid problem on the solid demo: one multi-angle reading set with
// spectra, one RGB BRDF sample; nothing is computed until fitRecipe runs.
FitProblem validProblem() {
    FitProblem p;
    p.recipe = test::demoRecipe("solid-red");
    p.free.push_back({"layers[1].components[0].volume_fraction", std::nullopt, std::nullopt});
    fit::MultiAngleMeasurement m = fit::standardMultiAngleMeasurement();
    for (auto& r : m.readings) r.reflectance_factor.assign(r.wavelengths_nm.size(), 0.1);
    p.observations.multi_angle.push_back(m);
    fit::BrdfMeasurement b;
    b.name = "gonio";
    b.samples.push_back({30.0, 0.0, 30.0, 180.0, {0.1, 0.05, 0.02}, 0.0});
    p.observations.brdf.push_back(b);
    return p;
}

// The field of the InputError that validateFitProblem throws.
std::string errorField(const FitProblem& p) {
    try {
        fit::validateFitProblem(p);
    } catch (const InputError& e) {
        return e.field();
    }
    return "<no error>";
}

TEST(FitParameterPaths, ListsTheDemoPearlsNumericFields) {
    const Recipe pearl = test::demoRecipe("pearlescent-two-layer");
    const auto paths = fit::listParameterPaths(pearl);
    const auto has = [&](const std::string& path) {
        return std::any_of(paths.begin(), paths.end(), [&](const auto& p) { return p.path == path; });
    };
    EXPECT_TRUE(has("layers[0].thickness_um"));
    EXPECT_TRUE(has("layers[1].components[0].volume_fraction"));
    EXPECT_TRUE(has("layers[1].components[0].tio2_thickness_nm"));
    EXPECT_TRUE(has("layers[1].components[1].volume_fraction"));
    EXPECT_TRUE(has("substrate.albedo"));  // a constant spectrum
    // Tabulated spectra are not one number.
    EXPECT_FALSE(has("layers[1].binder.refractive_index"));
    for (const auto& p : paths) {
        EXPECT_DOUBLE_EQ(fit::parameterValue(pearl, p.path), p.value) << p.path;
        EXPECT_LT(p.min, p.max) << p.path;
    }
}

// The default bounds are the allowed range but for a flake spread, whose
// lower bound is what both fit presets resolve: above the allowed 0 deg and
// at least the narrowest spread the fast model's rule resolves at standard.
TEST(FitParameterPaths, DefaultBoundsStartFlakeSpreadsWhereTheFitResolvesThem) {
    const Recipe pearl = test::demoRecipe("pearlescent-two-layer");
    for (const auto& p : fit::listParameterPaths(pearl)) {
        const fit::FitBounds bounds = fit::defaultFitBounds(p);
        EXPECT_DOUBLE_EQ(bounds.upper, p.max) << p.path;
        if (p.decl->key != "orientation_spread_deg") {
            EXPECT_DOUBLE_EQ(bounds.lower, p.min) << p.path;
            continue;
        }
        EXPECT_GT(bounds.lower, p.min) << p.path;
        EXPECT_GE(bounds.lower, narrowestResolvedFlakeSpreadDeg(fit::fitSettings(Preset::Standard)))
            << p.path;
        EXPECT_LT(bounds.lower, 3.0) << p.path;  // the real silver fit landed at 4.3 deg: it must stay open
    }
}

TEST(FitParameterPaths, SetAndGetRoundTrip) {
    Recipe r = test::demoRecipe("pearlescent-two-layer");
    fit::setParameterValue(r, "layers[1].components[1].volume_fraction", 0.02);
    EXPECT_DOUBLE_EQ(std::get<Pigment>(r.layers[1].components[1]).volume_fraction, 0.02);
    fit::setParameterValue(r, "substrate.albedo", 0.5);
    EXPECT_DOUBLE_EQ(std::get<LambertianSubstrate>(r.substrate).albedo(550.0), 0.5);
    // Depth-profile weights are addressable where a profile exists.
    std::get<InterferenceFlake>(r.layers[1].components[0]).depth_profile =
        DepthProfile{{0.0, 1.0}, {1.0, 1.0}};
    fit::setParameterValue(r, "layers[1].components[0].depth_profile.weight[1]", 2.0);
    EXPECT_DOUBLE_EQ(std::get<InterferenceFlake>(r.layers[1].components[0]).depth_profile->weight[1], 2.0);
}

TEST(FitParameterPaths, BadPathsNameThePath) {
    const Recipe r = test::demoRecipe("solid-red");
    for (const std::string path :
         {"layers[5].thickness_um", "layers[1].components[3].volume_fraction", "layers[1].bogus", "name",
          "layers[1].components[0].sigma_a_per_um" /* tabulated spectrum */}) {
        try {
            (void)fit::describeParameter(r, path);
            ADD_FAILURE() << path << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), path);
        }
    }
}

TEST(FitInputs, ValidProblemPasses) { EXPECT_EQ(errorField(validProblem()), "<no error>"); }

TEST(FitInputs, EachBadInputNamesItsField) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Case {
        std::string field;
        std::function<void(FitProblem&)> spoil;
    };
    const std::vector<Case> cases{
        {"multi_angle[0].readings[2].reflectance_factor[4]",
         [&](FitProblem& p) { p.observations.multi_angle[0].readings[2].reflectance_factor[4] = nan; }},
        {"multi_angle[0].readings[1].reflectance_factor[0]",
         [](FitProblem& p) { p.observations.multi_angle[0].readings[1].reflectance_factor[0] = -0.1; }},
        {"brdf[0].samples[0].values[1]",
         [](FitProblem& p) { p.observations.brdf[0].samples[0].values[1] = -1.0; }},
        {"brdf[0].samples[0].theta_i_deg",
         [&](FitProblem& p) { p.observations.brdf[0].samples[0].theta_i_deg = nan; }},
        {"brdf[0].samples", [](FitProblem& p) { p.observations.brdf[0].samples.clear(); }},
        {"multi_angle[0].readings", [](FitProblem& p) { p.observations.multi_angle[0].readings.clear(); }},
        {"observations", [](FitProblem& p) { p.observations = {}; }},
        {"multi_angle[0].readings[0].wavelengths_nm",
         [](FitProblem& p) {
             auto& r = p.observations.multi_angle[0].readings[0];
             for (double& w : r.wavelengths_nm) w += 1000.0;  // 1400-1700 nm: no overlap with 380-780
         }},
        {"multi_angle[0].readings[3].aspecular_deg",
         [](FitProblem& p) { p.observations.multi_angle[0].readings[3].aspecular_deg = 140.0; }},
        {"multi_angle[0].readings[2].azimuth_deg",
         [&](FitProblem& p) { p.observations.multi_angle[0].readings[2].azimuth_deg = nan; }},
        {"multi_angle[0].readings[2].azimuth_deg",
         [](FitProblem& p) { p.observations.multi_angle[0].readings[2].azimuth_deg = 200.0; }},
        {"multi_angle[0].readings[4].aspecular_deg",
         [](FitProblem& p) {
             // 45as75 turned 90° out of the plane about the specular direction
             // stays in front; at 15° illumination 15as100az30 is below the horizon.
             auto& r = p.observations.multi_angle[0].readings[4];
             r.illumination_deg = 15.0;
             r.aspecular_deg = 100.0;
             r.azimuth_deg = 30.0;
         }},
        {"multi_angle[0].side",
         [](FitProblem& p) { p.observations.multi_angle[0].side = fit::Side::Bottom; }},
        {"layers[1].components[0].volume_fraction",
         [](FitProblem& p) { p.free[0].upper = 0.9; }},  // allowed maximum 0.64
        {"layers[1].components[0].volume_fraction",
         [](FitProblem& p) {
             p.free[0].lower = 0.3;
             p.free[0].upper = 0.2;
         }},
        {"layers[9].thickness_um",
         [](FitProblem& p) {
             p.free.push_back({"layers[9].thickness_um", {}, {}});
         }},
        {"layers[1].components[0].sigma_s_per_um",
         [](FitProblem& p) {
             p.free.push_back({"layers[1].components[0].sigma_s_per_um", {}, {}});
         }},
        {"free", [](FitProblem& p) { p.free.clear(); }},
        {"layers[1].components[0].volume_fraction",
         [](FitProblem& p) { std::get<Pigment>(p.recipe.layers[1].components[0]).volume_fraction = 0.9; }},
        {"settings.starts", [](FitProblem& p) { p.settings.starts = 0; }},
    };
    for (const Case& c : cases) {
        FitProblem p = validProblem();
        c.spoil(p);
        EXPECT_EQ(errorField(p), c.field);
    }
}

TEST(FitInputs, SeenFromBelowNeedsATransparentSubstrate) {
    EXPECT_THROW((void)fit::recipeSeenFromBelow(test::demoRecipe("solid-red")), InputError);
    Recipe r = test::demoRecipe("pearlescent-two-layer");
    r.substrate = TransparentSubstrate{1.5};
    std::get<InterferenceFlake>(r.layers[1].components[0]).depth_profile =
        DepthProfile{{0.0, 0.25, 1.0}, {1.0, 2.0, 3.0}};
    const Recipe below = fit::recipeSeenFromBelow(r);
    ASSERT_EQ(below.layers.size(), 3U);  // carrier, basecoat, clear coat
    EXPECT_EQ(below.layers[1].name, "basecoat");
    EXPECT_EQ(below.layers[2].name, "clear coat");
    const auto& profile = *std::get<InterferenceFlake>(below.layers[1].components[0]).depth_profile;
    EXPECT_EQ(profile.depth, (std::vector<double>{0.0, 0.75, 1.0}));
    EXPECT_EQ(profile.weight, (std::vector<double>{3.0, 2.0, 1.0}));
    EXPECT_DOUBLE_EQ(std::get<TransparentSubstrate>(below.substrate).refractive_index, 1.0);
    // Turned over twice (without the two carriers) is the original.
    Recipe twice = fit::recipeSeenFromBelow(below);
    ASSERT_EQ(twice.layers.size(), 4U);
    twice.layers = {twice.layers[1], twice.layers[2]};
    EXPECT_EQ(twice.layers, r.layers);
}

}  // namespace
}  // namespace paintlab
