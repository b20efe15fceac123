#include "brdf_table_io.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/brdf_table_io.h"
#include "paintlab/engine/io/atomic_file.h"

namespace paintlab::cli {

std::string brdfTableText(const LayeredBrdf& brdf, const std::string& recipe_path,
                          const nlohmann::ordered_json& settings, double step_deg, bool csv,
                          const std::vector<LayeredBrdf>* batches) {
    return paintlab::brdfTableText(brdf, recipe_path, settings.dump(), step_deg, csv, batches);
}

bool isCsvPath(const std::string& path) { return isBrdfTableCsvPath(path); }

void writeTextFile(const std::string& path, const std::string& text, const std::string& option) {
    try {
        io::writeFileAtomically(path, text);
    } catch (const InputError& e) {
        throw InputError(e.source(), option, e.detail());
    }
}

}  // namespace paintlab::cli
