// The measured paints of shared/data/measured-brdf (tools/measured_brdf):
// the neural evaluator against the data's stated facts and a closed form,
// reciprocity of every model, the analytic fits against the neural ones at
// the multi-angle geometries, and the sampler's output on the BRDF-sample
// contract as `db import` / `fit --measurement` read it.

#include "paintlab/database/measurement_files.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/measured_brdf/paints.h"
#include "paintlab/measured_brdf/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::measured {
namespace {

const std::vector<MeasuredPaint>& paints() {
    static const std::vector<MeasuredPaint> all = loadMeasuredPaints(PAINTLAB_MEASURED_BRDF_DIR);
    return all;
}

const MeasuredPaint& paint(const std::string& key) {
    for (const MeasuredPaint& p : paints())
        if (p.neural.name() == key) return p;
    throw std::runtime_error("no paint " + key);
}

double luminance(const RgbValue& f) { return linearSrgbToXyz({f[0], f[1], f[2]}).Y; }

double luminanceAt(const RgbBrdf& brdf, double aspecular_deg) {
    const MultiAngleGeometry g = multiAngleGeometry(aspecular_deg);
    return luminance(brdf.eval(g.wi, g.wo));
}

// RMS over the sample directions and channels of the fit loss's log residual
// between f(wi, wo) and f(wo, wi), both weighted by cos θi of the first.
double reciprocityLogRms(const RgbBrdf& brdf) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const SampleDirection& d : sampleDirections()) {
        const Direction wi = d.wi();
        const Direction wo = d.wo();
        const RgbValue forward = brdf.eval(wi, wo);
        const RgbValue backward = brdf.eval(wo, wi);
        for (std::size_t c = 0; c < 3; ++c, ++n) {
            const double r = cosineLogResidual(forward[c], backward[c], wi.z);
            sum += r * r;
        }
    }
    return std::sqrt(sum / static_cast<double>(n));
}

// A BRDF that is not reciprocal (f grows with cos θi only), for checking that
// the reciprocity check can fail.
class NotReciprocal final : public RgbBrdf {
public:
    const std::string& name() const override { return m_name; }
    RgbValue eval(const Direction& wi, const Direction& wo) const override {
        if (wi.z <= 0.0 || wo.z <= 0.0) return {0.0, 0.0, 0.0};
        const double f = 2.0 * wi.z * wi.z;
        return {f, f, f};
    }

private:
    std::string m_name = "not reciprocal";
};

TEST(MeasuredBrdf, LoadsEveryPaintWithItsAnalyticFits) {
    ASSERT_EQ(paints().size(), 12u);
    std::size_t abc = 0;
    std::size_t sgd = 0;
    for (const MeasuredPaint& p : paints()) {
        abc += p.abc.has_value();
        sgd += p.sgd.has_value();
        EXPECT_EQ(p.abc.has_value(), p.neural.name().starts_with("MERL/")) << p.neural.name();
    }
    EXPECT_EQ(abc, 9u);
    EXPECT_EQ(sgd, 9u);
}

// Spectralon is a near-ideal diffuser of reflectance ~0.99: f = 0.99/π =
// 0.315 1/sr (the data's README: "about 0.31 everywhere"). Over the samples
// with θi, θo <= 60° (where the network was trained with most weight) the
// median is within 3 % of it; away from grazing (both <= 40°) every channel
// is within 10 %. Spectralon itself leaves Lambert towards grazing and
// near the specular (measured here: 0.27-0.40 at 60°), which is why the
// bound is on the median there.
TEST(MeasuredBrdf, SpectralonIsAnIdealDiffuser) {
    const RgbBrdf& spectralon = paint("RGL/spectralon_rgb").neural;
    constexpr double kLambert = 0.99 / std::numbers::pi;
    std::vector<double> values;
    std::size_t near_normal = 0;
    for (const SampleDirection& d : sampleDirections()) {
        if (d.theta_i_deg > 60.0 || d.theta_o_deg > 60.0) continue;
        const RgbValue f = spectralon.eval(d.wi(), d.wo());
        values.insert(values.end(), f.begin(), f.end());
        if (d.theta_i_deg > 40.0 || d.theta_o_deg > 40.0) continue;
        for (double v : f) EXPECT_NEAR(v, kLambert, 0.10 * kLambert) << d.theta_i_deg << " " << d.theta_o_deg;
        ++near_normal;
    }
    EXPECT_GT(near_normal, 300u);
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
    EXPECT_NEAR(values[values.size() / 2], kLambert, 0.03 * kLambert);
}

// The README's lightness flop, Y(45as15) / Y(45as110): about 50-110x for the
// MERL metallics, about 4.4x for pearl-paint (a pearl's flakes scatter far
// more light away from the specular than aligned metal flakes do).
TEST(MeasuredBrdf, LightnessFlopAsTheDataStates) {
    for (const char* key :
         {"MERL/silver-metallic-paint", "MERL/gold-metallic-paint", "MERL/blue-metallic-paint"}) {
        const RgbBrdf& f = paint(key).neural;
        const double flop = luminanceAt(f, 15.0) / luminanceAt(f, 110.0);
        EXPECT_GE(flop, 50.0) << key;
        EXPECT_LE(flop, 110.0) << key;
    }
    const RgbBrdf& pearl = paint("MERL/pearl-paint").neural;
    // "about 4.4": within 10 %.
    EXPECT_NEAR(luminanceAt(pearl, 15.0) / luminanceAt(pearl, 110.0), 4.4, 0.44);
}

// The analytic models are reciprocal by construction (symmetric in wi, wo):
// to rounding. The networks are not symmetric by construction (d becomes its
// mirror image about h when wi and wo swap), so reciprocity holds only to
// their fit error. Tolerance: an RMS log residual of 0.1, twice the noise
// the fit assumes for BRDF samples (observations.h, kDefaultBrdfLogNoise
// 0.05, the few per cent that MERL and RGL quote): the asymmetry is an error
// of the reconstruction of the order of the measurement's own. Measured
// (2026-12-05): 0.0014-0.027 for the MERL networks, 0.006-0.084 for RGL's
// (docs/VALIDATION.md); the metallic of RGL is the least reciprocal.
TEST(MeasuredBrdf, EveryModelIsReciprocal) {
    constexpr double kNetworkTolerance = 0.1;
    for (const MeasuredPaint& p : paints()) {
        const double rms = reciprocityLogRms(p.neural);
        EXPECT_LT(rms, kNetworkTolerance) << p.neural.name();
        if (p.abc) {
            EXPECT_LT(reciprocityLogRms(*p.abc), 1e-12) << p.neural.name();
        }
        if (p.sgd) {
            EXPECT_LT(reciprocityLogRms(*p.sgd), 1e-12) << p.neural.name();
        }
    }
    // The check can fail: a BRDF growing with cos²θi alone is far outside it.
    EXPECT_GT(reciprocityLogRms(NotReciprocal{}), 2.0 * kNetworkTolerance);
}

// Three reconstructions of one measurement must agree where the measurement
// is well determined. At the six multi-angle geometries the luminance of the
// published fits is within a factor 3 of the neural fit's wherever the
// neural value is above 2 % of its 45as-15 value (the deep flop of the
// glossiest paints is a few thousandths of the peak, below MERL's noise and
// where the reconstructions diverge most). A factor 3 (1.1 in ln) tells the
// same paint from another: the flop of every metallic here is 50-100x. The
// analytic fits were made over all of MERL's directions with their own
// error metrics, not at these six, so a tighter factor would test the fits,
// not this code. Measured: ABC 0.61-2.68, SGD 0.59-2.73, except SGD's fit of
// color-changing-paint1 (0.19-0.26 near the specular: its published error,
// 0.16, is among the table's worst), which is held to nothing here and
// reported in VALIDATION.md.
TEST(MeasuredBrdf, AnalyticFitsAgreeWithTheNeuralFitsAtTheMultiAngleGeometries) {
    for (const MeasuredPaint& p : paints()) {
        const double peak = luminanceAt(p.neural, -15.0);
        for (double aspecular : kAspecularAnglesDeg) {
            const double reference = luminanceAt(p.neural, aspecular);
            if (reference < 0.02 * peak) continue;
            const auto check = [&](const RgbBrdf& fit, const char* model) {
                const double ratio = luminanceAt(fit, aspecular) / reference;
                EXPECT_GT(ratio, 1.0 / 3.0) << p.neural.name() << " " << model << " 45as" << aspecular;
                EXPECT_LT(ratio, 3.0) << p.neural.name() << " " << model << " 45as" << aspecular;
            };
            if (p.abc) check(*p.abc, "ABC");
            if (p.sgd && p.neural.name() != "MERL/color-changing-paint1") check(*p.sgd, "SGD");
        }
    }
}

TEST(MeasuredBrdf, SamplesAreDeterministicStratifiedAndInRange) {
    const std::vector<SampleDirection> a = sampleDirections();
    ASSERT_EQ(a.size(), kDefaultSampleCount);
    const std::vector<SampleDirection> b = sampleDirections();
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].theta_i_deg, b[k].theta_i_deg);
        EXPECT_EQ(a[k].phi_o_deg, b[k].phi_o_deg);
        EXPECT_LE(a[k].theta_i_deg, kMaxThetaDeg);
        EXPECT_LE(a[k].theta_o_deg, kMaxThetaDeg + 0.005);
    }
    // Every 10° incidence band holds at least half its share of the samples.
    std::array<std::size_t, 8> bands{};
    for (const SampleDirection& d : a)
        ++bands[std::min<std::size_t>(7, static_cast<std::size_t>(d.theta_i_deg / 10.0))];
    for (std::size_t band : bands) EXPECT_GT(band, kDefaultSampleCount / 16);
    // The six multi-angle geometries are sampled exactly.
    for (double aspecular : kAspecularAnglesDeg) {
        const MultiAngleGeometry g = multiAngleGeometry(aspecular);
        const bool found = std::any_of(a.begin(), a.end(), [&](const SampleDirection& d) {
            const Direction wo = d.wo();
            return d.theta_i_deg == 45.0 && std::abs(wo.x - g.wo.x) < 1e-9 && std::abs(wo.z - g.wo.z) < 1e-9;
        });
        EXPECT_TRUE(found) << aspecular;
    }
    // Near the specular: at least a quarter of the samples within 10° of the mirror direction.
    const std::size_t near_specular =
        static_cast<std::size_t>(std::count_if(a.begin(), a.end(), [](const SampleDirection& d) {
            const Direction wi = d.wi();
            const Direction wo = d.wo();
            return -wi.x * wo.x - wi.y * wo.y + wi.z * wo.z > std::cos(10.0 * std::numbers::pi / 180.0);
        }));
    EXPECT_GT(near_specular, kDefaultSampleCount / 4);
    EXPECT_THROW(sampleDirections(99), InputError);
}

// The written file is what `db import` and `fit --measurement` read: an RGB
// BRDF measurement whose samples are the neural BRDF at the stated angles.
TEST(MeasuredBrdf, SamplesCsvIsOnTheBrdfSampleContract) {
    const MeasuredPaint& pearl = paint("MERL/pearl-paint");
    const std::vector<SampleDirection> directions = sampleDirections();
    db::Measurement description;
    description.name = "pearl-paint";
    const db::Measurement m =
        db::parseMeasurementCsv(samplesCsv(pearl.neural, directions), "pearl.csv", description);
    EXPECT_EQ(m.kind, db::MeasurementKind::Brdf);
    EXPECT_EQ(m.channels, (std::vector<std::string>{"R", "G", "B"}));
    ASSERT_EQ(m.samples.size(), directions.size());
    for (std::size_t k = 0; k < directions.size(); k += 97) {
        const db::BrdfSample& s = m.samples[k];
        const RgbValue f = pearl.neural.eval(directionFromAnglesDeg(s.theta_i_deg, s.phi_i_deg),
                                             directionFromAnglesDeg(s.theta_o_deg, s.phi_o_deg));
        for (std::size_t c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(s.values[c], f[c]);
    }
}

TEST(MeasuredBrdf, BadFilesAreClearErrors) {
    EXPECT_THROW(loadNeuralBrdfs("/nonexistent/nbrdf_paints.json"), InputError);
    try {
        loadAbcParameters(std::filesystem::path(PAINTLAB_MEASURED_BRDF_DIR) /
                          "merl_sgd_bagher2012_params.csv");
        FAIL() << "the SGD table read as ABC";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("kD_r"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace paintlab::measured
