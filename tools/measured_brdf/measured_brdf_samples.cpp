// measured_brdf_samples: writes every measured paint of shared/data/measured-brdf
// as BRDF samples on the contract of `paintlab-cli db import` / `fit
// --measurement` (one <stem>.csv each), and analytic_vs_neural.csv: per paint
// and published analytic fit, the cosine-weighted log error against the
// neural fit over the samples and ΔE00 at the six multi-angle geometries.
//   measured_brdf_samples --out DIR [--data DIR] [--count 2000] [--seed K]

#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/measured_brdf/paints.h"
#include "paintlab/measured_brdf/sampler.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>

namespace {

using namespace paintlab;
using namespace paintlab::measured;

std::string comparisonRow(const MeasuredPaint& paint, const char* model, const RgbBrdf& brdf,
                          const std::vector<SampleDirection>& directions) {
    const std::array<Lab, 6> ref = multiAngleLabs(paint.neural);
    const std::array<Lab, 6> lab = multiAngleLabs(brdf);
    std::vector<std::string> fields{io::csvField(paint.neural.name()), model,
                                    io::csvNumber(cosineLogRms(brdf, paint.neural, directions))};
    for (std::size_t k = 0; k < lab.size(); ++k) fields.push_back(io::csvNumber(ciede2000(lab[k], ref[k])));
    for (const Lab& l : lab) fields.push_back(io::csvNumber(l.L));
    return io::csvJoin(fields);
}

int run(int argc, char** argv) {
    CLI::App app{"Sample the measured paints' BRDFs on the BRDF-sample contract"};
    std::filesystem::path data = PAINTLAB_MEASURED_BRDF_DIR;
    std::filesystem::path out;
    std::size_t count = kDefaultSampleCount;
    std::uint64_t seed = kDefaultSampleSeed;
    app.add_option("--data", data, "folder of nbrdf_paints.json and the analytic-fit tables");
    app.add_option("--out", out, "folder to write the CSV files to")->required();
    app.add_option("--count", count, "samples per paint (>= 100)");
    app.add_option("--seed", seed, "seed of the directions");
    CLI11_PARSE(app, argc, argv);
    const std::vector<MeasuredPaint> paints = loadMeasuredPaints(data);
    const std::vector<SampleDirection> directions = sampleDirections(count, seed);
    std::filesystem::create_directories(out);
    std::string header = "paint,model,log_error";
    for (double a : kAspecularAnglesDeg) header += ",de00_45as" + io::formatNumber(a);
    for (double a : kAspecularAnglesDeg) header += ",L_45as" + io::formatNumber(a);
    std::string comparison = header + "\n";
    for (const MeasuredPaint& paint : paints) {
        io::writeFileAtomically(out / (paint.stem + ".csv"), samplesCsv(paint.neural, directions));
        comparison += comparisonRow(paint, "neural", paint.neural, directions);
        if (paint.abc) comparison += comparisonRow(paint, "abc", *paint.abc, directions);
        if (paint.sgd) comparison += comparisonRow(paint, "sgd", *paint.sgd, directions);
    }
    io::writeFileAtomically(out / "analytic_vs_neural.csv", comparison);
    std::cout << comparison;
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const paintlab::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    } catch (...) {
        return 1;
    }
}
