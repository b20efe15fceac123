#pragma once
// Storing and reading rows of the spectrum table (wavelengths and values as
// JSON arrays of numbers, written with enough digits to read back the same doubles).

#include "paintlab/database/ingredients.h"
#include "sqlite.h"

#include <cstdint>
#include <string_view>

namespace paintlab::db::detail {

std::int64_t insertSpectrum(const Connection& connection, std::string_view quantity, const Spectrum& spectrum,
                            const SpectrumInfo& info);
// Throws InputError(file, "spectrum <id>", ...) if there is no such row and
// DatabaseError (Reason::Corrupt) if its arrays do not make a spectrum.
StoredSpectrum selectSpectrum(const Connection& connection, std::int64_t id);

}  // namespace paintlab::db::detail
