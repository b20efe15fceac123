// The MERL BRDF binary (plugins/merl): the geometry against MERL's own
// look-up, write-then-read at every index, a Lambertian recipe exported as
// albedo/pi everywhere, and bad files refused with the file named.

#include "merl_format.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

namespace paintlab::plugins::merl {
namespace {

std::filesystem::path tempFile(const std::string& name) {
    return std::filesystem::temp_directory_path() / name;
}

double dot(const Direction& a, const Direction& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// MERL's std_coords_to_half_diff_coords (BRDFRead.cpp), written out
// independently of binDirections: half vector, then the light direction
// rotated by -phi_half about the normal and -theta_half about the binormal.
void halfDiff(const Direction& wi, const Direction& wo, double& theta_half, double& theta_diff,
              double& phi_diff) {
    Direction h{wi.x + wo.x, wi.y + wo.y, wi.z + wo.z};
    const double n = std::sqrt(dot(h, h));
    h = {h.x / n, h.y / n, h.z / n};
    theta_half = std::acos(std::clamp(h.z, -1.0, 1.0));
    const double phi_half = std::atan2(h.y, h.x);
    const double cp = std::cos(-phi_half);
    const double sp = std::sin(-phi_half);
    const Direction t{wi.x * cp - wi.y * sp, wi.x * sp + wi.y * cp, wi.z};  // about z
    const double ct = std::cos(-theta_half);
    const double st = std::sin(-theta_half);
    const Direction d{t.x * ct + t.z * st, t.y, -t.x * st + t.z * ct};  // about y
    theta_diff = std::acos(std::clamp(d.z, -1.0, 1.0));
    phi_diff = std::atan2(d.y, d.x);
}

// A smooth, non-reciprocity-breaking test function with a different shape per channel.
Rgb analytic(const Direction& wi, const Direction& wo) {
    Direction h{wi.x + wo.x, wi.y + wo.y, wi.z + wo.z};
    const double hz = h.z / std::sqrt(dot(h, h));
    return {0.1 + 0.05 * wi.z * wo.z, 0.2 + std::pow(hz, 20.0),
            0.3 + 0.1 * (wi.z + wo.z) + 5.0 * std::pow(hz, 200.0)};
}

TEST(Merl, BinCentresLookUpToTheirOwnBinInMerlsConvention) {
    // Every bin whose directions are above the horizon (below it the angles
    // are not a reflection): MERL's look-up of the centre's angles is the bin.
    std::size_t checked = 0;
    for (std::size_t i = 0; i < kEntries; ++i) {
        const BinIndex bin = binOf(i);
        ASSERT_EQ(flatIndex(bin), i);
        const auto [wi, wo] = binDirections(bin);
        EXPECT_NEAR(dot(wi, wi), 1.0, 1e-12);
        EXPECT_NEAR(dot(wo, wo), 1.0, 1e-12);
        if (wi.z <= 0.0 || wo.z <= 0.0) continue;
        double th = 0.0, td = 0.0, pd = 0.0;
        halfDiff(wi, wo, th, td, pd);
        const BinIndex back = lookup(th, td, pd);
        ASSERT_EQ(flatIndex(back), i) << bin.theta_half << ' ' << bin.theta_diff << ' ' << bin.phi_diff;
        ++checked;
    }
    EXPECT_GT(checked, kEntries / 2);
}

// The export's progress (ExportOptions::progress): one report per theta_half
// bin, ending at 1; a false answer stops the tabulation with ExportCancelled
// long before all bins are done.
TEST(Merl, TabulationReportsProgressAndStopsWhenCancelled) {
    std::atomic<int> reports{0};
    std::atomic<bool> reached_one{false};
    (void)tabulate(analytic, [&](double fraction) {
        ++reports;
        if (fraction == 1.0) reached_one = true;
        return true;
    });
    EXPECT_EQ(reports.load(), kThetaHalfBins);
    EXPECT_TRUE(reached_one.load());
    std::atomic<int> evaluated{0};
    const auto counting = [&](const Direction& wi, const Direction& wo) {
        ++evaluated;
        return analytic(wi, wo);
    };
    EXPECT_THROW((void)tabulate(counting, [](double) { return false; }), ExportCancelled);
    // Each worker finishes the bin it is in (16,200 entries); a few bins at most, not 90.
    EXPECT_LT(evaluated.load(), static_cast<int>(kEntries / 10));
}

TEST(Merl, WriteThenReadGivesTheFunctionBackAtEveryIndex) {
    const Table written = tabulate(analytic);
    const auto file = tempFile("paintlab_merl_round_trip.binary");
    io::writeFileAtomically(file, encode(written));
    EXPECT_EQ(std::filesystem::file_size(file), kFileBytes);
    const Table read = readFile(file);
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < kEntries; ++i) {
            // Stored as f / scale, read as x * scale: a few rounding errors of a double.
            ASSERT_NEAR(read.rgb[c * kEntries + i], written.rgb[c * kEntries + i],
                        4e-16 * std::abs(written.rgb[c * kEntries + i]))
                << binOf(i).theta_half << ' ' << binOf(i).theta_diff << ' ' << binOf(i).phi_diff;
        }
    // Through the plugin, every measured bin above the horizon: each sample's
    // values are the function at the sample's own angles.
    ReadOptions options;
    options.max_samples = kEntries;
    const auto* importer = Registry::global().measurementImporterFor(file);
    ASSERT_NE(importer, nullptr);
    ASSERT_EQ(importer->format().id, "merl-binary");
    const db::Measurement m = importer->read(file, options);
    EXPECT_EQ(m.name, "paintlab_merl_round_trip");
    EXPECT_EQ(m.channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_GT(m.samples.size(), kEntries / 2);
    for (const auto& s : m.samples) {
        const Rgb f = analytic(directionFromAnglesDeg(s.theta_i_deg, s.phi_i_deg),
                               directionFromAnglesDeg(s.theta_o_deg, s.phi_o_deg));
        // Angles pass through degrees, acos and atan2 (~1e-13 rad); the
        // sharpest lobe (hz^200) changes by 200 * 1e-13 relative at most.
        ASSERT_NEAR(s.values[0], f.r, 1e-10 * f.r);
        ASSERT_NEAR(s.values[1], f.g, 1e-10 * f.g);
        ASSERT_NEAR(s.values[2], f.b, 1e-10 * f.b);
    }
    // The default subsampling keeps the stated number.
    EXPECT_EQ(importer->read(file, {}).samples.size(), kDefaultSamples);
    std::filesystem::remove(file);
}

TEST(Merl, LambertianRecipeExportsAlbedoOverPiEverywhere) {
    Recipe recipe;
    recipe.name = "white-ish panel";
    const std::vector<double> wavelengths = {380.0, 480.0, 580.0, 680.0, 780.0};
    const std::vector<double> albedo = {0.2, 0.35, 0.5, 0.65, 0.8};
    recipe.substrate = LambertianSubstrate{Spectrum(wavelengths, albedo)};
    // One clear layer of the ambient's index (the fast model needs a layer):
    // no interface, no absorption, no scattering, so f is rho/pi exactly.
    Layer clear;
    clear.name = "index-matched clear";
    clear.thickness_um = 1.0;
    clear.binder.refractive_index = Spectrum(1.0);
    recipe.layers.push_back(clear);
    // A Lambertian needs only order 0; few nodes and bands keep 1.46 million evaluations quick.
    FastModelSettings settings = presetSettings(Preset::Preview);
    settings.nodes = 4;
    settings.orders = 1;
    settings.bands = 5;
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, settings);
    // The truth: rho(lambda)/pi at the BRDF's bands (albedo is linear between
    // its samples), in linear sRGB.
    std::vector<double> f;
    for (const double nm : brdf.wavelengthsNm())
        f.push_back(Spectrum(wavelengths, albedo)(nm) / std::numbers::pi);
    const Rgb truth = weightedLinearSrgb(bandColourWeights(brdf.wavelengthsNm()), f);

    const auto file = tempFile("paintlab_merl_lambertian.binary");
    const auto* exporter = Registry::global().exporterFor(file);
    ASSERT_NE(exporter, nullptr);
    exporter->write(recipe, brdf, file, {});
    const Table table = readFile(file);
    for (std::size_t i = 0; i < kEntries; ++i) {
        // The fast model's Lambertian substrate is rho/pi to rounding (no
        // layer, so no adding-doubling error); the file stores it exactly.
        ASSERT_NEAR(table.rgb[i], truth.r, 1e-12) << i;
        ASSERT_NEAR(table.rgb[kEntries + i], truth.g, 1e-12) << i;
        ASSERT_NEAR(table.rgb[2 * kEntries + i], truth.b, 1e-12) << i;
    }
    std::filesystem::remove(file);
}

// Each bad file: InputError naming the file.
void expectRefused(const std::string& name, const std::string& bytes, const std::string& what) {
    const auto file = tempFile(name);
    io::writeFileAtomically(file, bytes);
    const auto* importer = Registry::global().measurementImporterFor(file);
    ASSERT_NE(importer, nullptr) << name;
    ASSERT_EQ(importer->format().id, "merl-binary") << name;
    try {
        (void)importer->read(file, {});
        ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), file.string());
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
    std::filesystem::remove(file);
}

std::string setValue(std::string bytes, std::size_t channel, std::size_t flat, double value) {
    std::memcpy(bytes.data() + kHeaderBytes + (channel * kEntries + flat) * sizeof(double), &value,
                sizeof(double));
    return bytes;
}

TEST(Merl, BadFilesAreRefusedNamingTheFile) {
    const std::string good = encode(tabulate(analytic));
    // The file's own size is named (it once said 12, the header's).
    expectRefused("paintlab_merl_truncated.binary", good.substr(0, good.size() / 2),
                  "the file has " + std::to_string(good.size() / 2) +
                      " bytes; a 90 x 90 x 180 MERL file has " + std::to_string(kFileBytes) + " (truncated)");
    expectRefused("paintlab_merl_header_only.binary", good.substr(0, 8), "truncated");
    expectRefused("paintlab_merl_long.binary", good + std::string(8, '\0'), "bytes");
    std::string huge = good.substr(0, 64);
    const std::array<std::int32_t, 3> dims = {10000, 10000, 10000};  // 10^12 samples claimed
    std::memcpy(huge.data(), dims.data(), sizeof dims);
    expectRefused("paintlab_merl_huge.binary", huge, "10000 x 10000 x 10000 (1e+12 samples");
    const std::size_t valid = flatIndex({10, 20, 30});  // above the horizon
    expectRefused("paintlab_merl_nan.binary", setValue(good, 1, valid, std::nan("")),
                  "G[theta_half 10, theta_diff 20, phi_diff 30]");
    expectRefused("paintlab_merl_negative.binary", setValue(good, 2, valid, -0.5), "is negative");
    std::mt19937 random(29);
    std::string noise(5000, '\0');
    for (char& c : noise) c = static_cast<char>(random() & 0xff);
    expectRefused("paintlab_merl_noise.binary", noise, "a MERL BRDF file has 90 x 90 x 180");
    // MERL's own mark of an unmeasured entry is accepted, and skipped.
    const auto file = tempFile("paintlab_merl_unmeasured.binary");
    io::writeFileAtomically(file, setValue(good, 0, valid, -1.0));
    ReadOptions all;
    all.max_samples = kEntries;
    const db::Measurement m = Registry::global().measurementImporterFor(file)->read(file, all);
    const db::Measurement full = toMeasurement(decode(good, "good"), kEntries, {});
    EXPECT_EQ(m.samples.size() + 1, full.samples.size());
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace paintlab::plugins::merl
