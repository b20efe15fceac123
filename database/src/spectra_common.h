#pragma once
// Shared by the readers of named-spectrum files. Private to the database library.

#include "paintlab/database/spectra_files.h"

#include <string>
#include <vector>

namespace paintlab::db::detail {

// Checks names (not empty, unique in the file) and quantities, and converts
// every unit to its canonical one. labels[i] names spectra[i] in messages.
// Throws InputError(source, labels[i] + ".<field>", ...).
void finishNamedSpectra(std::vector<NamedSpectrum>& spectra, const std::vector<std::string>& labels,
                        const std::string& source);

}  // namespace paintlab::db::detail
