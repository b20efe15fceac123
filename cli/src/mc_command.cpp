// `mc` and `compare`: the Monte Carlo full model from the command line, and
// its comparison with the fast model at the multi-angle geometries.
// Options and JSON fields are a public contract (issue 4): extend, never rename.

#include "brdf_table_io.h"
#include "commands.h"
#include "helper_commands.h"

#include "paintlab/database/measurements.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/montecarlo/cone_average.h"
#include "paintlab/engine/montecarlo/mc_table.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/spectrum.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

namespace paintlab::cli {

namespace {

using nlohmann::ordered_json;

struct McOptions {
    std::string recipe;
    // Unset: -1 and NaN (so that an explicit 0 is rejected, not ignored).
    std::int64_t samples = -1;
    double rel_error = std::numeric_limits<double>::quiet_NaN();
    double abs_error = std::numeric_limits<double>::quiet_NaN();  // 1/sr, with --rel-error
    double seconds = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t seed = 1;
    int bands = 8;
    std::string preset = "standard";
    std::string out;
    bool json = false;
    bool explicit_flakes = false;
    double cone_deg = 0.0;  // 0: next-event estimator (explicit flakes default to 5)
    bool reject_overlaps = false;
    bool disk_flakes = false;     // explicit flakes: exact disks instead of 16-gons
    bool histogram_only = false;  // explicit flakes: the cone histogram alone (no connections)
    int tile_views = 32;          // explicit flakes: azimuths each tile is traced at
    int batches = mc::McSettings{}.batches;
    std::string bottom_operator = "on";     // the flake-free bottom as one reflecting surface (mc_bottom.h)
    std::string chain_connections = "all";  // chain connections: all flake layers, on: mirror ones, off
    bool table = false;                     // mc: tabulate on the fast model's basis (mc_table.h)
    double step_deg = 5.0;                  // mc --table: angular step of the written table
};

constexpr std::int64_t kDefaultSamples = 20000;
constexpr double kSummaryMinNm = 400.0;  // compare's summary range
constexpr double kSummaryMaxNm = 700.0;
constexpr std::int64_t kMaxSamples = 1000000000;

// The stop rule from the options: exactly one of --samples, --rel-error, --seconds (default: samples).
mc::McSettings mcSettings(const McOptions& o) {
    const bool has_samples = o.samples != -1;
    const bool has_rel_error = !std::isnan(o.rel_error);
    const bool has_seconds = !std::isnan(o.seconds);
    if (int(has_samples) + int(has_rel_error) + int(has_seconds) > 1)
        throw InputError("<argument>", "--samples/--rel-error/--seconds", "give at most one stopping rule");
    if (has_samples && !(o.samples >= 1 && o.samples <= kMaxSamples))
        throw InputError("<argument>", "--samples", std::to_string(o.samples) + " must be in [1, 1e9]");
    if (has_rel_error && !(o.rel_error >= 1e-4 && o.rel_error < 1.0))
        throw InputError("<argument>", "--rel-error", std::to_string(o.rel_error) + " must be in [1e-4, 1)");
    const bool has_abs_error = !std::isnan(o.abs_error);
    if (has_abs_error && !has_rel_error) throw InputError("<argument>", "--abs-error", "needs --rel-error");
    if (has_abs_error && !(o.abs_error > 0.0 && o.abs_error <= 1.0))
        throw InputError("<argument>", "--abs-error",
                         std::to_string(o.abs_error) + " must be in (0, 1] 1/sr");
    if (has_seconds && !(o.seconds > 0.0 && o.seconds <= 86400.0))
        throw InputError("<argument>", "--seconds", std::to_string(o.seconds) + " must be in (0, 86400]");
    if (!(o.cone_deg >= 0.0 && o.cone_deg <= 30.0))
        throw InputError("<argument>", "--cone", std::to_string(o.cone_deg) + " must be in [0, 30] degrees");
    if (o.reject_overlaps && !o.explicit_flakes)
        throw InputError("<argument>", "--reject-overlaps", "needs --explicit-flakes");
    if (o.disk_flakes && !o.explicit_flakes)
        throw InputError("<argument>", "--disk-flakes", "needs --explicit-flakes");
    if (o.histogram_only && !o.explicit_flakes)
        throw InputError("<argument>", "--histogram-only", "needs --explicit-flakes");
    if (!(o.tile_views >= 1 && o.tile_views <= 1024))
        throw InputError("<argument>", "--tile-views",
                         std::to_string(o.tile_views) + " must be in [1, 1024]");
    if (!(o.batches >= 1 && o.batches <= 256))
        throw InputError("<argument>", "--batches", std::to_string(o.batches) + " must be in [1, 256]");
    mc::McSettings s;
    s.seed = o.seed;
    s.explicit_flakes = o.explicit_flakes;
    s.reject_overlaps = o.reject_overlaps;
    if (o.disk_flakes) s.flake_polygon_sides = 0;
    s.connections = !o.histogram_only;
    s.split_branches = !o.histogram_only;  // --histogram-only: the analog walk, no split branches
    s.tile_views = o.tile_views;
    s.batches = o.batches;
    s.bottom_operator = o.bottom_operator == "on";
    s.mirror_chain_connections = o.chain_connections != "off";
    s.interference_chain_connections = o.chain_connections == "all";
    s.histogram_cone_deg = o.cone_deg > 0.0 ? o.cone_deg : (o.explicit_flakes ? 5.0 : 0.0);
    s.max_paths = has_samples ? o.samples : kDefaultSamples;
    if (has_rel_error) {
        s.max_paths = kMaxSamples;
        s.target_rel_error = o.rel_error;
        if (has_abs_error) s.target_abs_error_per_sr = o.abs_error;
        s.max_seconds = 600.0;  // a safety net, reported in the settings
    }
    if (has_seconds) {
        s.max_paths = kMaxSamples;
        s.max_seconds = o.seconds;
    }
    return s;
}

ProgressCallback terminalProgress(const char* what) {
    if (isatty(STDERR_FILENO) == 0) return {};
    return [what](double fraction) {
        std::fprintf(stderr, "\r%s: %3.0f%%", what, 100.0 * fraction);
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        return true;
    };
}

// Incidence 0 (albedo only) and 45 degrees with the six multi-angle detectors.
std::vector<mc::IncidenceRequest> multiAngleRequests() {
    mc::IncidenceRequest normal{directionFromAnglesDeg(0.0, 0.0), {}};
    mc::IncidenceRequest oblique{multiAngleGeometry(kAspecularAnglesDeg[0]).wi, {}};
    for (double as : kAspecularAnglesDeg) oblique.wo.push_back(multiAngleGeometry(as).wo);
    return {normal, oblique};
}

// exit: index into brdf_per_sr, or kAlbedo / kTransmittance.
constexpr int kAlbedo = -1;
constexpr int kTransmittance = -2;

ordered_json estimatesJson(const mc::McResult& r, std::size_t incidence, int exit) {
    std::vector<double> mean;
    std::vector<double> se;
    for (const auto& band : r.bands) {
        const auto& inc = band[incidence];
        const auto& e = exit == kAlbedo          ? inc.albedo
                        : exit == kTransmittance ? inc.transmittance
                                                 : inc.brdf_per_sr[static_cast<std::size_t>(exit)];
        mean.push_back(e.mean);
        se.push_back(e.std_error);
    }
    return {{"mean", mean}, {"std_error", se}};
}

// Where a run's time went: per (band, incidence) job its paths, seconds and
// largest relative standard error (the albedo's or an f's), and where.
struct JobAccount {
    double wavelength_nm = 0.0;
    double theta_i_deg = 0.0;
    std::int64_t paths = 0;
    double seconds = 0.0;
    double largest_rel_error = 0.0;
    std::string at = "albedo";
    mc::RateAccount account;
    std::string account_worst;  // the account's worst cone, named like `at`
};

std::vector<JobAccount> jobAccounts(const mc::McResult& r) {
    const double incidence_deg[] = {0.0, kMultiAngleIlluminationDeg};
    std::vector<JobAccount> jobs;
    for (std::size_t b = 0; b < r.bands.size(); ++b)
        for (std::size_t i = 0; i < r.bands[b].size() && i < std::size(incidence_deg); ++i) {
            const mc::IncidenceResult& inc = r.bands[b][i];
            JobAccount job{r.wavelengths_nm[b],
                           incidence_deg[i],
                           inc.paths,
                           inc.seconds,
                           0.0,
                           "albedo",
                           inc.account,
                           ""};
            if (inc.account.measured && inc.account.worst_exit < kAspecularAnglesDeg.size())
                job.account_worst =
                    db::multiAngleGeometryName(incidence_deg[i], kAspecularAnglesDeg[inc.account.worst_exit]);
            const auto consider = [&job](const mc::Estimate& e, const std::string& where) {
                if (!(std::abs(e.mean) > 0.0)) return;
                const double rel = e.std_error / std::abs(e.mean);
                if (rel > job.largest_rel_error) {
                    job.largest_rel_error = rel;
                    job.at = where;
                }
            };
            consider(inc.albedo, "albedo");
            for (std::size_t k = 0; k < inc.brdf_per_sr.size() && k < kAspecularAnglesDeg.size(); ++k)
                consider(inc.brdf_per_sr[k],
                         db::multiAngleGeometryName(incidence_deg[i], kAspecularAnglesDeg[k]));
            jobs.push_back(job);
        }
    return jobs;
}

// The rate model's parts (mc::RateAccount::Part), as the JSON names them.
constexpr std::array<const char*, mc::RateAccount::kParts> kRateParts = {"walk", "next_event", "glints",
                                                                         "reverse_walks", "delta_walks"};

ordered_json jobsJson(const std::vector<JobAccount>& jobs) {
    ordered_json out = ordered_json::array();
    for (const JobAccount& j : jobs) {
        ordered_json job = {{"wavelength_nm", j.wavelength_nm},
                            {"theta_i_deg", j.theta_i_deg},
                            {"paths", j.paths},
                            {"seconds", j.seconds},
                            {"largest_rel_error", j.largest_rel_error},
                            {"at", j.at}};
        if (j.account.measured && !j.account_worst.empty()) {
            ordered_json cost;
            ordered_json variance;
            for (std::size_t p = 0; p < kRateParts.size(); ++p) {
                cost[kRateParts[p]] = j.account.cost_us_per_path[p];
                variance[kRateParts[p]] = j.account.rel_variance_per_path[p];
            }
            job["rate_model"] = {{"worst", j.account_worst},
                                 {"cost_us_per_path", std::move(cost)},
                                 {"rel_variance_per_path", std::move(variance)}};
        }
        out.push_back(std::move(job));
    }
    return out;
}

ordered_json settingsJson(const mc::McSettings& s, const mc::McResult& r) {
    return {{"seed", s.seed},
            {"explicit_flakes", s.explicit_flakes},
            {"histogram_cone_deg", s.histogram_cone_deg},
            {"reject_overlaps", s.reject_overlaps},
            {"flake_shape", s.flake_polygon_sides == 0 ? std::string("disk")
                                                       : std::to_string(s.flake_polygon_sides) + "-gon"},
            {"batches", s.batches},
            {"bottom_operator", s.bottom_operator},
            {"chain_connections", s.mirror_chain_connections || s.interference_chain_connections},
            {"chain_connections_layers", s.interference_chain_connections ? "all flake layers"
                                         : s.mirror_chain_connections     ? "mirror-flake layers"
                                                                          : "none"},
            {"connections", s.explicit_flakes && s.connections},
            {"tile_views", s.explicit_flakes ? s.tile_views : 1},
            {"glint_azimuths", s.explicit_flakes && s.connections && s.glint_azimuths},
            {"move_glint_flakes", s.explicit_flakes && s.connections && s.glint_azimuths &&
                                      s.move_glint_flakes && !s.reject_overlaps},
            {"adaptive_fractions",
             s.explicit_flakes && s.connections && s.glint_azimuths && s.adaptive_fractions},
            {"split_branches", s.explicit_flakes && s.split_branches},
            {"reverse_walks", s.explicit_flakes && s.connections && s.glint_azimuths && s.reverse_walks},
            {"reflected_beams",
             s.explicit_flakes && s.connections && s.glint_azimuths && s.reverse_walks && s.reflected_beams},
            {"top_images",
             s.explicit_flakes && s.connections && s.glint_azimuths && s.reverse_walks && s.top_images},
            {"delta_walks", s.explicit_flakes && s.connections && s.glint_azimuths && s.delta_walks},
            {"first_flake_walks",
             s.explicit_flakes && s.connections && s.glint_azimuths && s.delta_walks && s.first_flake_walks},
            // The roulette by promise takes its cone weights from the adaptive model.
            {"chain_promise", s.explicit_flakes && s.connections && s.glint_azimuths &&
                                  s.adaptive_fractions && s.delta_walks && s.chain_promise},
            {"flake_images", s.explicit_flakes && s.connections && s.glint_azimuths && s.flake_images},
            {"max_paths", s.max_paths},
            {"target_rel_error", s.target_rel_error},
            {"target_abs_error_per_sr", s.target_abs_error_per_sr},
            {"max_seconds", s.max_seconds},
            {"paths", r.total_paths},
            {"compute_seconds", r.seconds}};
}

void emit(const McOptions& o, const std::string& text) {
    if (o.out.empty()) {
        std::cout << text;
        return;
    }
    writeTextFile(o.out, text, "--out");
    std::cerr << "wrote " << o.out << '\n';
}

void checkBands(int bands) {
    if (bands < 2 || bands > 81)
        throw InputError("<argument>", "--bands", std::to_string(bands) + " must be in [2, 81]");
}

Preset parsePreset(const std::string& name) {
    try {
        return presetFromName(name);
    } catch (const InputError& e) {
        throw InputError("<argument>", "--preset", e.detail());
    }
}

// mc --table: the full model on the fast model's basis of --preset, written
// like `brdf --out` (with standard errors), or summarised at the multi-angle geometries.
int runMcTable(const McOptions& o) {
    const mc::McSettings settings = mcSettings(o);
    const Preset preset = parsePreset(o.preset);
    if (!(o.step_deg >= 0.5 && o.step_deg <= 45.0))
        throw InputError("<argument>", "--step", "must be between 0.5 and 45 degrees");
    const Recipe recipe = loadRecipeFile(o.recipe);
    const FastModelSettings grid = presetSettings(preset);
    const mc::McTable table = mc::tabulateMonteCarlo(recipe, grid, settings, terminalProgress("mc table"));
    const std::vector<LayeredBrdf>* batches = table.batch_brdfs.empty() ? nullptr : &table.batch_brdfs;
    if (o.json || !o.out.empty()) {
        ordered_json s;
        s["model"] = "monte_carlo";
        s["preset"] = o.preset;
        s["nodes"] = grid.nodes;
        s["orders"] = grid.orders;
        s["bands"] = grid.bands;
        s["slices"] = grid.slices;
        s["compute_seconds"] = table.seconds;
        mc::McResult summary;
        summary.total_paths = table.total_paths;
        summary.seconds = table.seconds;
        s["monte_carlo"] = settingsJson(settings, summary);
        const bool csv = isCsvPath(o.out);
        const std::string text = brdfTableText(table.brdf, o.recipe, s, o.step_deg, csv, batches);
        if (o.out.empty()) {
            std::cout << text;
        } else {
            writeTextFile(o.out, text, "--out");
            std::cerr << "wrote " << o.out << " (" << (csv ? "CSV" : "JSON") << ", "
                      << table.brdf.wavelengthsNm().size() << " bands, " << table.seconds << " s)\n";
        }
        return 0;
    }
    std::printf("Monte Carlo table on the %s grid: %lld paths in %.2f s (seed %llu)\n", o.preset.c_str(),
                static_cast<long long>(table.total_paths), table.seconds,
                static_cast<unsigned long long>(settings.seed));
    std::printf("%10s", "lambda_nm");
    for (double as : kAspecularAnglesDeg) std::printf("   f 45as%-4g (1/sr)", as);
    std::printf("\n");
    const auto wavelengths = table.brdf.wavelengthsNm();
    for (std::size_t b = 0; b < wavelengths.size(); ++b) {
        std::printf("%10.1f", wavelengths[b]);
        for (double as : kAspecularAnglesDeg) {
            const MultiAngleGeometry g = multiAngleGeometry(as);
            std::vector<double> per_batch;
            if (batches != nullptr)
                for (const auto& batch : *batches) per_batch.push_back(batch.eval(g.wi, g.wo)[b]);
            std::printf(" %11.5g+-%-7.2g", table.brdf.eval(g.wi, g.wo)[b],
                        mc::batchEstimate(per_batch).std_error);
        }
        std::printf("\n");
    }
    for (const auto& note : mc::estimatorLimitations(recipe)) std::printf("note: %s\n", note.c_str());
    return 0;
}

int runMc(const McOptions& o) {
    if (o.table) return runMcTable(o);
    checkBands(o.bands);
    const mc::McSettings settings = mcSettings(o);
    const Recipe recipe = loadRecipeFile(o.recipe);
    const auto wavelengths = visibleBands(static_cast<std::size_t>(o.bands));
    const auto requests = multiAngleRequests();
    const mc::McResult r = mc::runMonteCarlo(recipe, wavelengths, requests, settings, terminalProgress("mc"));
    std::ostringstream text;
    if (o.json || (!o.out.empty())) {
        ordered_json out;
        out["recipe"] = o.recipe;
        out["settings"] = settingsJson(settings, r);
        out["wavelengths_nm"] = wavelengths;
        ordered_json albedo = ordered_json::array();
        albedo.push_back({{"theta_i_deg", 0.0}, {"albedo", estimatesJson(r, 0, kAlbedo)}});
        albedo.push_back(
            {{"theta_i_deg", kMultiAngleIlluminationDeg}, {"albedo", estimatesJson(r, 1, kAlbedo)}});
        out["albedo"] = std::move(albedo);  // directional-hemispherical, mirror term included
        ordered_json transmittance = ordered_json::array();
        transmittance.push_back(
            {{"theta_i_deg", 0.0}, {"transmittance", estimatesJson(r, 0, kTransmittance)}});
        transmittance.push_back({{"theta_i_deg", kMultiAngleIlluminationDeg},
                                 {"transmittance", estimatesJson(r, 1, kTransmittance)}});
        out["transmittance"] = std::move(transmittance);  // into a transparent substrate (0 for others)
        ordered_json geometries = ordered_json::array();
        for (std::size_t k = 0; k < kAspecularAnglesDeg.size(); ++k)
            geometries.push_back({{"aspecular_deg", kAspecularAnglesDeg[k]},
                                  {"brdf_per_sr", estimatesJson(r, 1, static_cast<int>(k))}});
        out["geometries"] = std::move(geometries);  // mirror term excluded
        out["jobs"] = jobsJson(jobAccounts(r));     // where the time went
        out["notes"] = mc::estimatorLimitations(recipe);
        text << out.dump(1) << '\n';
    } else {
        std::printf("Monte Carlo, %lld paths in %.2f s (seed %llu)\n", static_cast<long long>(r.total_paths),
                    r.seconds, static_cast<unsigned long long>(settings.seed));
        std::printf("%10s %20s %20s", "lambda_nm", "albedo 0deg", "albedo 45deg");
        for (double as : kAspecularAnglesDeg) std::printf("   f 45as%-4g (1/sr)", as);
        std::printf("\n");
        for (std::size_t b = 0; b < wavelengths.size(); ++b) {
            const auto& band = r.bands[b];
            std::printf("%10.1f %11.5f+-%-7.5f %11.5f+-%-7.5f", wavelengths[b], band[0].albedo.mean,
                        band[0].albedo.std_error, band[1].albedo.mean, band[1].albedo.std_error);
            for (const auto& e : band[1].brdf_per_sr) std::printf(" %11.5g+-%-7.2g", e.mean, e.std_error);
            std::printf("\n");
        }
        const auto jobs = jobAccounts(r);
        const auto slowest = std::max_element(
            jobs.begin(), jobs.end(), [](const auto& a, const auto& b) { return a.seconds < b.seconds; });
        if (slowest != jobs.end())
            std::printf("slowest job: %.1f nm at %g deg, %.2f s, %lld paths, largest error %.2f %% (%s)\n",
                        slowest->wavelength_nm, slowest->theta_i_deg, slowest->seconds,
                        static_cast<long long>(slowest->paths), 100.0 * slowest->largest_rel_error,
                        slowest->at.c_str());
        for (const auto& note : mc::estimatorLimitations(recipe)) std::printf("note: %s\n", note.c_str());
    }
    if (!text.str().empty()) emit(o, text.str());
    return 0;
}

int runCompare(const McOptions& o) {
    const mc::McSettings settings = mcSettings(o);
    const Preset preset = parsePreset(o.preset);
    const Recipe recipe = loadRecipeFile(o.recipe);
    const LayeredBrdf fast =
        computeLayeredBrdf(recipe, presetSettings(preset), terminalProgress("fast model"));
    const auto wavelengths = fast.wavelengthsNm();
    const auto requests = multiAngleRequests();
    const mc::McResult r = mc::runMonteCarlo(recipe, wavelengths, requests, settings, terminalProgress("mc"));
    // Per geometry: the band-mean f of both models, their relative difference
    // and the largest |z| over bands (z = (mc - fast) / se_mc).
    ordered_json geometries = ordered_json::array();
    struct Row {
        double aspecular, fast_mean, mc_mean, mc_se, rel, max_z;
    };
    std::vector<Row> rows;
    for (std::size_t k = 0; k < kAspecularAnglesDeg.size(); ++k) {
        const MultiAngleGeometry g = multiAngleGeometry(kAspecularAnglesDeg[k]);
        const auto f_fast = mc::coneAverage(fast, g.wi, g.wo, settings.histogram_cone_deg);
        Row row{kAspecularAnglesDeg[k], 0.0, 0.0, 0.0, 0.0, 0.0};
        std::vector<double> f_mc;
        std::vector<double> se;
        double var = 0.0;
        double nb = 0.0;
        for (std::size_t b = 0; b < wavelengths.size(); ++b) {
            const auto& e = r.bands[b][1].brdf_per_sr[k];
            f_mc.push_back(e.mean);
            se.push_back(e.std_error);
            // The summary covers 400-700 nm, where the fast model computes its
            // colour bands (outside it extrapolates; layered_brdf.h output_bands).
            if (wavelengths[b] < kSummaryMinNm || wavelengths[b] > kSummaryMaxNm) continue;
            nb += 1.0;
            row.fast_mean += f_fast[b];
            row.mc_mean += e.mean;
            var += e.std_error * e.std_error;
            if (e.std_error > 0.0)
                row.max_z = std::max(row.max_z, std::abs(e.mean - f_fast[b]) / e.std_error);
        }
        nb = std::max(nb, 1.0);
        row.fast_mean /= nb;
        row.mc_mean /= nb;
        row.mc_se = std::sqrt(var) / nb;
        row.rel = row.fast_mean > 0.0 ? (row.mc_mean - row.fast_mean) / row.fast_mean : 0.0;
        rows.push_back(row);
        geometries.push_back({{"aspecular_deg", row.aspecular},
                              {"fast_brdf_per_sr", f_fast},
                              {"mc_brdf_per_sr", f_mc},
                              {"mc_std_error", se},
                              {"band_mean_relative_difference", row.rel},
                              {"max_abs_z", row.max_z}});
    }
    if (o.json) {
        ordered_json out;
        out["recipe"] = o.recipe;
        out["preset"] = o.preset;
        out["fast_seconds"] = fast.computeSeconds();
        out["mc_seconds"] = r.seconds;
        out["mc_settings"] = settingsJson(settings, r);
        out["wavelengths_nm"] = std::vector<double>(wavelengths.begin(), wavelengths.end());
        out["geometries"] = std::move(geometries);
        out["notes"] = mc::estimatorLimitations(recipe);
        emit(o, out.dump(1) + '\n');
        return 0;
    }
    std::ostringstream text;
    char line[256];
    std::snprintf(line, sizeof line, "fast model (%s): %.3f s; Monte Carlo: %.2f s, %lld paths\n",
                  o.preset.c_str(), fast.computeSeconds(), r.seconds, static_cast<long long>(r.total_paths));
    text << line;
    std::snprintf(line, sizeof line, "%10s %14s %14s %12s %10s %8s\n", "geometry", "fast f (1/sr)",
                  "MC f (1/sr)", "MC std err", "rel diff", "max|z|");
    text << line;
    for (const auto& row : rows) {
        std::snprintf(line, sizeof line, "  45as%-4g %14.6g %14.6g %12.2g %9.2f%% %8.2f\n", row.aspecular,
                      row.fast_mean, row.mc_mean, row.mc_se, 100.0 * row.rel, row.max_z);
        text << line;
    }
    text << "(band means over the bands in 400-700 nm; z per band = (MC - fast) / MC std err";
    if (settings.histogram_cone_deg > 0.0)
        text << "; both averaged over a " << settings.histogram_cone_deg << " deg cone";
    if (settings.explicit_flakes) text << "; explicit flakes";
    text << ")\n";
    for (const auto& note : mc::estimatorLimitations(recipe)) text << "note: " << note << '\n';
    emit(o, text.str());
    return 0;
}

void addStopOptions(CLI::App* command, McOptions& o) {
    command->add_option("recipe", o.recipe, "Recipe JSON file")->required();
    command->add_option("--samples", o.samples, "Paths per band and incidence (default 20000)");
    command->add_option("--rel-error", o.rel_error, "Stop at this relative standard error of every estimate");
    command->add_option("--abs-error", o.abs_error,
                        "With --rel-error: an f (1/sr) also counts as converged once its standard error is "
                        "at or below this (near-black values, whose 1 % no instrument resolves)");
    command->add_option("--seconds", o.seconds,
                        "Time budget in seconds (shared evenly by bands and incidences)");
    command->add_option("--seed", o.seed, "Random seed (same seed, same numbers)")->capture_default_str();
    command->add_option("--out", o.out, "Write the output to this file");
    command->add_flag("--json", o.json, "Print JSON");
    command->add_flag("--explicit-flakes", o.explicit_flakes,
                      "Trace explicit flakes in a periodic tile (Embree) instead of the continuum");
    command->add_option("--cone", o.cone_deg,
                        "Histogram estimator: cone half-angle in degrees (default: next-event; 5 with "
                        "--explicit-flakes); f is then the cone average");
    command->add_flag("--reject-overlaps", o.reject_overlaps,
                      "With --explicit-flakes: re-draw flakes that would intersect one already placed");
    command->add_flag("--disk-flakes", o.disk_flakes,
                      "With --explicit-flakes: exact disks instead of regular 16-gons of the disk's area");
    command->add_flag("--histogram-only", o.histogram_only,
                      "With --explicit-flakes: score f by the cone histogram alone, without the "
                      "connections through the tile or split branches (same mean, larger errors)");
    command
        ->add_option("--tile-views", o.tile_views,
                     "With --explicit-flakes: azimuths of the incidence plane each tile is traced at "
                     "(flake statistics are isotropic; more views, less spread between tiles)")
        ->capture_default_str();
    command
        ->add_option("--bottom-operator", o.bottom_operator,
                     "on: the layers below the lowest flakes and the substrate are one reflecting "
                     "surface, their reflection operator by adding-doubling (where it has no mirror "
                     "part); off: the walk crosses them")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    command
        ->add_option("--chain-connections", o.chain_connections,
                     "With --explicit-flakes: on: the chains of mirror reflections in layers of mirror "
                     "flakes whose last flake is met once, or that leave a cavity between two flakes the "
                     "way they came, are scored by connections through a flake drawn with the tiles' law; "
                     "all: the same on every flake layer, interference flakes too; "
                     "off: the walks land them in the cones by chance")
        ->check(CLI::IsMember({"on", "all", "off"}))
        ->capture_default_str();
    command
        ->add_option("--batches", o.batches,
                     "Batches of paths (each its own flake tile with --explicit-flakes; the standard "
                     "errors are then over the batches)")
        ->capture_default_str();
}

}  // namespace

void addMcCommands(CLI::App& app, CommandAction& action) {
    auto o = std::make_shared<McOptions>();

    CLI::App* mc = app.add_subcommand(kMcCommand.name, kMcCommand.description);
    addStopOptions(mc, *o);
    mc->add_option("--bands", o->bands, "Wavelength bands over 380-780 nm")->capture_default_str();
    mc->add_flag(
        "--table", o->table,
        "Tabulate the BRDF on the fast model's basis (--preset's grid and bands); --out FILE.json|.csv "
        "writes it like `brdf --out`, with standard errors");
    mc->add_option("--preset", o->preset, "With --table: the fast-model preset whose grid is used")
        ->capture_default_str();
    mc->add_option("--step", o->step_deg, "With --table: angular step of the written table in degrees")
        ->capture_default_str();
    mc->callback([o, &action] { action = [o] { return runMc(*o); }; });

    CLI::App* compare = app.add_subcommand(kCompareCommand.name, kCompareCommand.description);
    addStopOptions(compare, *o);
    compare->add_option("--preset", o->preset, "Fast-model preset (its bands are the MC's bands)")
        ->capture_default_str();
    compare->callback([o, &action] { action = [o] { return runCompare(*o); }; });
}

}  // namespace paintlab::cli
