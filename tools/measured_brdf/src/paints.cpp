#include "paintlab/measured_brdf/paints.h"

#include "paintlab/engine/multiangle.h"

#include <algorithm>
#include <cctype>

namespace paintlab::measured {

std::vector<MeasuredPaint> loadMeasuredPaints(const std::filesystem::path& dir) {
    std::vector<NeuralBrdf> neural = loadNeuralBrdfs(dir / "nbrdf_paints.json");
    const std::vector<AbcParameters> abc = loadAbcParameters(dir / "merl_abc_low2012_params.csv");
    const std::vector<SgdParameters> sgd = loadSgdParameters(dir / "merl_sgd_bagher2012_params.csv");
    std::vector<MeasuredPaint> out;
    for (NeuralBrdf& n : neural) {
        const std::string key = n.name();
        std::string stem = key;
        std::replace(stem.begin(), stem.end(), '/', '-');
        std::transform(stem.begin(), stem.end(), stem.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        MeasuredPaint paint{std::move(n), stem, std::nullopt, std::nullopt};
        if (key.starts_with("MERL/")) {
            const std::string merl = key.substr(5);
            for (const AbcParameters& p : abc)
                if (p.name == merl) paint.abc.emplace(p);
            for (const SgdParameters& p : sgd)
                if (p.name == merl) paint.sgd.emplace(p);
        }
        out.push_back(std::move(paint));
    }
    return out;
}

std::array<Lab, 6> multiAngleLabs(const RgbBrdf& brdf) {
    std::array<Lab, 6> out{};
    for (std::size_t k = 0; k < kAspecularAnglesDeg.size(); ++k) {
        const MultiAngleGeometry g = multiAngleGeometry(kAspecularAnglesDeg[k]);
        out[k] = reflectanceFactorLab(brdf.eval(g.wi, g.wo));
    }
    return out;
}

}  // namespace paintlab::measured
