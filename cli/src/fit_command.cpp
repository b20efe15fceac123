// `fit TEMPLATE.json (--measurement FILE | --db-measurement NAME)...
//  [--bottom-measurement FILE|NAME] --free PATH[=LO:HI]... [--starts N] [--seed K]
//  [--out FITTED.json] [--save --author A --note T] [--json]`: a recipe from
// measurements (engine fit/fit.h, issue 28). `fit --help` with a template
// lists its addressable parameter paths. Options and JSON fields are a public
// contract: extend, never rename.

#include "commands.h"
#include "db_cli.h"
#include "helper_commands.h"

#include "paintlab/database/exchange.h"
#include "paintlab/database/fit_observations.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/plugins/registry.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace paintlab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

constexpr int kExitCancelled = 130;  // as a shell reports a command stopped by Ctrl+C

struct FitOptions {
    std::string template_file;
    std::vector<std::string> measurement_files;
    std::vector<std::string> db_measurements;
    std::string bottom_measurement;
    std::string db_file;
    std::vector<std::string> free;
    int starts = fit::FitSettings{}.starts;
    std::uint64_t seed = fit::FitSettings{}.seed;
    std::string search_preset = "preview";
    std::string polish_preset = "standard";
    std::string out;
    bool save = false;
    std::string author;
    std::string note;
    bool json = false;
    bool list_parameters = false;
};

std::atomic<bool> g_interrupted{false};

extern "C" void onInterrupt(int /*signal*/) { g_interrupted = true; }

// "PATH" or "PATH=LO:HI" (either bound may be empty: "PATH=:0.2").
fit::FreeParameter parseFree(const std::string& text, std::size_t index) {
    const std::string field = "--free[" + std::to_string(index) + "]";
    fit::FreeParameter p;
    const auto eq = text.find('=');
    p.path = text.substr(0, eq);
    if (p.path.empty()) throw InputError("<argument>", field, "'" + text + "' names no parameter path");
    if (eq == std::string::npos) return p;
    const std::string range = text.substr(eq + 1);
    const auto colon = range.find(':');
    if (colon == std::string::npos)
        throw InputError("<argument>", field, "'" + text + "': give bounds as PATH=LO:HI (e.g. =0.01:0.2)");
    const auto number = [&](std::string_view part) -> std::optional<double> {
        if (part.empty()) return std::nullopt;
        double value = 0.0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (error != std::errc() || end != part.data() + part.size() || !std::isfinite(value))
            throw InputError("<argument>", field,
                             "'" + std::string(part) + "' is not a number in '" + text + "'");
        return value;
    };
    p.lower = number(std::string_view(range).substr(0, colon));
    p.upper = number(std::string_view(range).substr(colon + 1));
    return p;
}

std::string parameterListing(const Recipe& recipe) {
    std::string out = "Addressable parameters of '" + recipe.name +
                      "' (--free PATH[=LO:HI]; default bounds "
                      "in brackets: the allowed range, or what the fit resolves):\n";
    for (const auto& p : fit::listParameterPaths(recipe)) {
        const fit::FitBounds bounds = fit::defaultFitBounds(p);
        out += "  " + p.path + "  = " + io::formatNumber(p.value) + " " + std::string(p.decl->unit) + "  [" +
               io::formatNumber(bounds.lower) + ", " + io::formatNumber(bounds.upper) + "]" +
               (p.log_scale_suited ? "  (log scale)" : "") + "\n      " + p.label + "\n";
    }
    return out;
}

// A measurement named on the command line: a file if one exists at that
// path (or it ends in .csv / .json), else a database measurement's name.
struct NamedMeasurement {
    db::Measurement measurement;
    bool from_file = false;
};

// Every format `db import` reads: the plugins' (MERL, ...) and the database's JSON/CSV.
NamedMeasurement readMeasurementFile(const std::string& file) {
    return {plugins::readMeasurementFile(file, {}, 0), true};
}

NamedMeasurement readDbMeasurement(db::Database& database, const std::string& name) {
    auto m = db::findMeasurement(database, name);
    if (!m)
        throw InputError(database.file().string(), "measurement '" + name + "'",
                         "no such measurement (paintlab-cli db measurements lists them)");
    return {std::move(*m), false};
}

bool looksLikeFile(const std::string& text) {
    if (fs::exists(text)) return true;
    // A name ending in an extension some measurement importer claims (the registry's, not a list here).
    std::string extension = fs::path(text).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const auto& loaded : plugins::Registry::global().plugins())
        for (const auto* offer : loaded.plugin->measurementImporters()) {
            const auto extensions = offer->format().extensions;
            if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) return true;
        }
    return false;
}

std::string defaultAuthor() {
    if (const char* user = std::getenv("USER"); user != nullptr && *user != '\0') return user;
    return "paintlab";
}

ordered_json labJson(const Lab& lab) { return {{"L", lab.L}, {"a", lab.a}, {"b", lab.b}}; }

ordered_json numberOrNull(double value) {
    return std::isfinite(value) ? ordered_json(value) : ordered_json();
}

ordered_json resultJson(const fit::FitResult& r, const FitOptions& o, const std::vector<std::string>& names) {
    ordered_json parameters = ordered_json::array();
    for (const auto& p : r.parameters)
        parameters.push_back({{"path", p.path},
                              {"label", p.label},
                              {"unit", p.unit},
                              {"initial", p.initial},
                              {"value", p.value},
                              {"sigma", numberOrNull(p.sigma)},
                              {"lower", p.lower},
                              {"upper", p.upper},
                              {"at_bound", p.at_bound},
                              {"determined", p.determined}});
    ordered_json geometries = ordered_json::array();
    for (const auto& g : r.geometries) {
        ordered_json entry{{"measurement", g.measurement},
                           {"side", std::string(fit::sideName(g.side))},
                           {"illumination_deg", g.illumination_deg},
                           {"aspecular_deg", g.aspecular_deg}};
        if (!isInPlane(g.azimuth_deg)) entry["azimuth_deg"] = g.azimuth_deg;  // out of the plane only
        entry["delta_e00"] = g.delta_e00;
        entry["measured_lab"] = labJson(g.measured);
        entry["fitted_lab"] = labJson(g.fitted);
        entry["wavelengths_nm"] = g.wavelengths_nm;
        entry["fitted_reflectance_factor"] = g.fitted_reflectance_factor;
        geometries.push_back(std::move(entry));
    }
    ordered_json residuals = ordered_json::array();
    for (const auto& x : r.residuals)
        residuals.push_back(
            {{"measurement", x.measurement},
             {"index", x.index},
             {"kind", x.kind == fit::ObservationKind::BrdfSample           ? "brdf_sample"
                      : x.kind == fit::ObservationKind::MultiAngleSpectral ? "multiangle_spectral"
                                                                           : "multiangle_lab"},
             {"side", std::string(fit::sideName(x.side))},
             {"whitened_rms", x.whitened_rms},
             {"log_error", x.log_error}});
    ordered_json identifiability = ordered_json::array();
    for (const auto& i : r.identifiability)
        identifiability.push_back(
            {{"kind", i.kind == fit::IdentifiabilityKind::Correlated     ? "correlated"
                      : i.kind == fit::IdentifiabilityKind::Undetermined ? "undetermined"
                                                                         : "at_bound"},
             {"paths", i.paths},
             {"correlation", i.correlation},
             {"message", i.message}});
    ordered_json alternatives = ordered_json::array();
    for (const auto& a : r.alternatives)
        alternatives.push_back({{"cost", a.cost}, {"values", a.values}, {"max_delta_e00", a.max_delta_e00}});
    ordered_json correlation = ordered_json::array();
    for (const double c : r.correlation) correlation.push_back(numberOrNull(c));
    return {{"template_file", o.template_file},
            {"recipe", r.recipe.name},
            {"measurements", names},
            {"starts", o.starts},
            {"seed", o.seed},
            {"search_preset", o.search_preset},
            {"polish_preset", o.polish_preset},
            {"cost", r.cost},
            {"residual_count", r.residual_count},
            {"reduced_chi_square", r.reduced_chi_square},
            {"parameters", parameters},
            {"correlation", correlation},
            {"geometries", geometries},
            {"residuals", residuals},
            {"identifiability", identifiability},
            {"alternatives", alternatives},
            {"evaluations", r.evaluations},
            {"seconds", r.seconds},
            {"model_share", r.modelShare()}};
}

void printResult(const fit::FitResult& r, const std::vector<std::string>& names) {
    std::printf("fit of '%s' to", r.recipe.name.c_str());
    for (const auto& n : names) std::printf(" '%s'", n.c_str());
    std::printf(
        ": cost %.4g over %zu residuals (reduced chi-square %.3g), %ld evaluations, %.1f s (%.0f %% in "
        "the fast model)\n",
        r.cost, r.residual_count, r.reduced_chi_square, r.evaluations, r.seconds, 100.0 * r.modelShare());
    std::printf("parameters (value +- 1 sigma):\n");
    for (const auto& p : r.parameters) {
        const std::string sigma = std::isfinite(p.sigma) ? io::formatNumber(p.sigma) : "undetermined";
        std::printf("  %-48s %12s +- %-12s %s  [%s, %s]%s\n", p.path.c_str(),
                    io::formatNumber(p.value).c_str(), sigma.c_str(), p.unit.c_str(),
                    io::formatNumber(p.lower).c_str(), io::formatNumber(p.upper).c_str(),
                    p.at_bound ? "  at bound" : "");
    }
    if (!r.geometries.empty()) {
        std::printf("multi-angle geometries (measured vs fitted):\n");
        for (const auto& g : r.geometries) {
            // "45as15 " as before; out-of-plane names ("45as25az90") take the room they need.
            std::string name = db::multiAngleGeometryName(g.illumination_deg, g.aspecular_deg, g.azimuth_deg);
            const std::size_t width = name.find("as") + 6;
            if (name.size() < width) name.resize(width, ' ');
            std::printf("  %-6s %s  dE00 %6.2f   L*a*b* %6.2f %6.2f %6.2f  vs %6.2f %6.2f %6.2f\n",
                        std::string(fit::sideName(g.side)).c_str(), name.c_str(), g.delta_e00, g.measured.L,
                        g.measured.a, g.measured.b, g.fitted.L, g.fitted.a, g.fitted.b);
        }
    }
    for (const auto& i : r.identifiability) std::printf("warning: %s\n", i.message.c_str());
    if (!r.alternatives.empty()) {
        std::printf("alternative recipes that look nearly the same (cost, values in the order above):\n");
        for (const auto& a : r.alternatives) {
            std::printf("  cost %.4g, max dE00 %.2f:", a.cost, a.max_delta_e00);
            for (const double v : a.values) std::printf(" %s", io::formatNumber(v).c_str());
            std::printf("\n");
        }
    }
}

fit::FitProgressCallback terminalProgress(bool show) {
    using Clock = std::chrono::steady_clock;
    auto last = std::make_shared<Clock::time_point>();
    return [show, last](const fit::FitProgress& p) {
        if (show && Clock::now() - *last > std::chrono::milliseconds(250)) {
            *last = Clock::now();
            std::fprintf(stderr, "\rfit: %3.0f%%  %s %d/%d, best cost %.4g, %ld evaluations   ",
                         100.0 * p.fraction, p.stage.c_str(), p.start, p.starts, p.best_cost, p.evaluations);
        }
        return !g_interrupted.load();
    };
}

// Stores the file measurements the fit used that the database lacks (an
// identical one of the same name is reused), the fitted recipe as a new
// version and one `fit` row per measurement.
void saveFit(const FitOptions& o, const fit::FitResult& result, const fit::FitProblem& problem,
             const std::vector<NamedMeasurement>& used) {
    db::Database database = openCliDatabase(o.db_file, false);
    for (const auto& u : used) {
        if (!u.from_file) continue;
        auto stored = db::findMeasurement(database, u.measurement.name);
        if (!stored) {
            db::createMeasurement(database, u.measurement);
            continue;
        }
        stored->id = 0;
        if (!(*stored == u.measurement))
            throw InputError(database.file().string(), "measurement '" + u.measurement.name + "'",
                             "a different measurement of this name is stored; rename the file or import it "
                             "under another name (db measurement-import --name) and use --db-measurement");
    }
    db::SaveOptions save;
    save.author = o.author.empty() ? defaultAuthor() : o.author;
    save.note = o.note.empty() ? "fitted to measurements" : o.note;
    save.source = o.template_file;
    const db::SavedVersion version = db::saveRecipeVersion(database, result.recipe, save);
    for (const auto& row : db::fitRecords(result, problem, version.recipe_name, version.version, save.note))
        db::recordFit(database, row);
    std::fprintf(stderr, "saved '%s' version %d and %zu fit record(s) in %s\n", version.recipe_name.c_str(),
                 version.version, problem.observations.multi_angle.size() + problem.observations.brdf.size(),
                 database.file().string().c_str());
}

int runFit(const FitOptions& o) {
    const Recipe recipe = loadRecipeFile(o.template_file);
    if (o.list_parameters) {
        std::cout << parameterListing(recipe);
        return 0;
    }
    if (o.free.empty())
        throw InputError(
            "<argument>", "--free",
            "name at least one parameter to fit (paintlab-cli fit TEMPLATE --parameters lists them)");
    std::vector<NamedMeasurement> used;
    std::optional<db::Database> database;
    const auto db = [&]() -> db::Database& {
        if (!database) database.emplace(openCliDatabase(o.db_file, false));
        return *database;
    };
    fit::FitProblem problem;
    problem.recipe = recipe;
    for (const auto& file : o.measurement_files) used.push_back(readMeasurementFile(file));
    for (const auto& name : o.db_measurements) used.push_back(readDbMeasurement(db(), name));
    const std::size_t top_count = used.size();
    if (!o.bottom_measurement.empty())
        used.push_back(looksLikeFile(o.bottom_measurement) ? readMeasurementFile(o.bottom_measurement)
                                                           : readDbMeasurement(db(), o.bottom_measurement));
    if (used.empty()) throw InputError("<argument>", "--measurement", "give at least one measurement to fit");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < used.size(); ++i) {
        db::addFitObservation(problem.observations, used[i].measurement,
                              i < top_count ? fit::Side::Top : fit::Side::Bottom);
        names.push_back(used[i].measurement.name);
    }
    for (std::size_t i = 0; i < o.free.size(); ++i) problem.free.push_back(parseFree(o.free[i], i));
    problem.settings.starts = o.starts;
    problem.settings.seed = o.seed;
    problem.settings.search_preset = presetFromName(o.search_preset);
    problem.settings.polish_preset = presetFromName(o.polish_preset);
    fit::validateFitProblem(problem);  // every bad input before any work

    g_interrupted = false;
    const auto previous = std::signal(SIGINT, onInterrupt);
    fit::FitResult result;
    const bool show = isatty(STDERR_FILENO) != 0;
    try {
        result = fit::fitRecipe(problem, terminalProgress(show));
    } catch (const fit::FitCancelled&) {
        std::signal(SIGINT, previous);
        std::fprintf(stderr, "\nfit cancelled: nothing written or saved\n");
        return kExitCancelled;
    }
    std::signal(SIGINT, previous);
    if (show) std::fprintf(stderr, "\n");

    if (!o.out.empty()) io::writeFileAtomically(o.out, recipeToJson(result.recipe));
    if (o.save) saveFit(o, result, problem, used);
    if (o.json)
        std::cout << resultJson(result, o, names).dump(2) << '\n';
    else
        printResult(result, names);
    return 0;
}

}  // namespace

void addFitCommand(CLI::App& app, CommandAction& action) {
    auto o = std::make_shared<FitOptions>();
    CLI::App* cmd = app.add_subcommand(kFitCommand.name, kFitCommand.description);
    cmd->add_option("template", o->template_file,
                    "Template recipe JSON file (its values are the first guess)")
        ->required();
    cmd->add_option("--measurement", o->measurement_files,
                    "Measurement file (any format db import reads: JSON, CSV, MERL .binary, ...), seen from "
                    "the top; repeatable");
    cmd->add_option("--db-measurement", o->db_measurements,
                    "A measurement stored in the database, by name, seen from the top; repeatable");
    cmd->add_option("--bottom-measurement", o->bottom_measurement,
                    "File or database name of a measurement through the transparent substrate, from below");
    cmd->add_option("--db", o->db_file, "Database file (default: the user's)");
    cmd->add_option("--free", o->free,
                    "Parameter to fit, PATH or PATH=LO:HI (default bounds: the allowed range); repeatable");
    cmd->add_option("--starts", o->starts, "Multi-start points (low-discrepancy, inside the bounds)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--seed", o->seed, "Seed of the starts (the same seed gives the same result)")
        ->capture_default_str();
    cmd->add_option("--search-preset", o->search_preset, "Preset of the multi-start search")
        ->capture_default_str();
    cmd->add_option("--polish-preset", o->polish_preset, "Preset of the polish and the report")
        ->capture_default_str();
    cmd->add_option("--out", o->out, "Write the fitted recipe to this recipe file");
    cmd->add_flag("--save", o->save, "Store the fitted recipe as a new version and the fit in the database");
    cmd->add_option("--author", o->author, "Who saves the fitted version (default: the login name)");
    cmd->add_option("--note", o->note, "Why (stored with the version and the fit)");
    cmd->add_flag("--json", o->json, "JSON output");
    cmd->add_flag("--parameters", o->list_parameters,
                  "List the template's addressable parameter paths and exit");
    // --help with a template lists its parameters too (the positional is
    // converted before CLI11 handles --help).
    cmd->footer([o] {
        if (o->template_file.empty())
            return std::string("Give a template before --help to list its parameters.");
        try {
            return parameterListing(loadRecipeFile(o->template_file));
        } catch (const std::exception& e) {
            return std::string("(cannot list the parameters: ") + e.what() + ")";
        }
    });
    cmd->callback([o, &action] { action = [o] { return runFit(*o); }; });
}

}  // namespace paintlab::cli
