// Writes the converged values of tests/data/reference/sharp_phase_slabs.csv:
// reads the Monte Carlo reference of tools/reference_slab (its grid of slabs
// and directions, its values and standard errors) and adds the fast model at
// two settings far beyond the reference preset (96 nodes and Legendre
// moments with 64 Fourier orders, the truth the tests use, and 72 with 48,
// which shows that it has converged). 96 nodes is the most the tables'
// interpolation takes (computeLayeredBrdf refuses more). Not a test: run
// by hand when the grid changes (tests/README.md, "Reference data").
//
//   sharp_phase_reference MC.csv > tests/data/reference/sharp_phase_slabs.csv
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/io/csv.h"

#include "test_recipes.h"

#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

namespace {

using namespace paintlab;

FastModelSettings converged(int nodes, int orders) {
    FastModelSettings s;
    s.nodes = nodes;  // also the Legendre moments kept: f = g^nodes
    s.orders = orders;
    s.bands = 2;
    s.max_start_tau = 1.0 / 4096.0;
    s.order_tolerance = 1e-12;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: sharp_phase_reference MC.csv\n";
        return 2;
    }
    std::ifstream in(argv[1]);
    std::stringstream text;
    text << in.rdbuf();
    const io::CsvTable mc = io::CsvTable::parse(text.str(), argv[1]);
    mc.requireColumns({"albedo", "optical_thickness", "g", "theta_i_deg", "theta_o_deg", "phi_o_deg",
                       "brdf_per_sr", "standard_error_per_sr"});
    std::map<std::tuple<double, double, double>, std::pair<LayeredBrdf, LayeredBrdf>> slabs;
    std::cout << "albedo,optical_thickness,g,theta_i_deg,theta_o_deg,phi_o_deg,mc_brdf_per_sr,"
                 "mc_standard_error_per_sr,converged_brdf_per_sr,coarser_brdf_per_sr\n";
    for (const auto& record : mc.records()) {
        const auto number = [&](const char* column) { return mc.requiredNumber(record, column); };
        const auto key = std::make_tuple(number("albedo"), number("optical_thickness"), number("g"));
        auto it = slabs.find(key);
        if (it == slabs.end()) {
            Recipe r = test::oneLayerRecipe(1.0, 1.0, BlackSubstrate{});
            r.layers[0].components = {test::rawMedium(std::get<0>(key), std::get<1>(key), std::get<2>(key))};
            std::cerr << "slab " << mc.field(record, "albedo") << ' ' << mc.field(record, "optical_thickness")
                      << ' ' << mc.field(record, "g") << '\n';
            it = slabs
                     .emplace(key, std::make_pair(computeLayeredBrdf(r, converged(96, 64)),
                                                  computeLayeredBrdf(r, converged(72, 48))))
                     .first;
        }
        const Direction wi = directionFromAnglesDeg(number("theta_i_deg"), 0.0);
        const Direction wo = directionFromAnglesDeg(number("theta_o_deg"), number("phi_o_deg"));
        std::vector<std::string> fields;
        for (const char* column : {"albedo", "optical_thickness", "g", "theta_i_deg", "theta_o_deg",
                                   "phi_o_deg", "brdf_per_sr", "standard_error_per_sr"})
            fields.push_back(mc.field(record, column));
        fields.push_back(io::csvNumber(it->second.first.eval(wi, wo)[0]));
        fields.push_back(io::csvNumber(it->second.second.eval(wi, wo)[0]));
        std::cout << io::csvJoin(fields);
    }
    return 0;
}
