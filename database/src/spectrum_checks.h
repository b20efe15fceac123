#pragma once
// What every imported spectrum must be, whatever file it came from, and the
// units an import accepts. Private to the database library.
//
// Units: a spectrum is stored in the unit its quantity is declared with
// (parameters.h: "1" dimensionless, "1/µm" per length). An import may give
// it in another unit of the same dimension and is converted:
//   dimensionless: "1", "%" (x 0.01)
//   per length:    "1/nm" (x 1e3), "1/µm" = "1/um", "1/mm" (x 1e-3), "1/cm" (x 1e-4), "1/m" (x 1e-6)
//   per steradian: "1/sr" (BRDF values)
// Anything else is an unknown unit and refused.

#include "paintlab/database/ingredients.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db::detail {

struct UnitConversion {
    std::string unit;     // the canonical unit ("1", "1/µm", "1/sr")
    double factor = 1.0;  // stored value = factor * given value
};

// The canonical unit and factor of a unit text; nullopt if it is unknown.
std::optional<UnitConversion> canonicalUnit(std::string_view unit);

// A spectrum from imported samples. Throws InputError(source, field, ...)
// naming the offending sample ("wavelengths_nm[3]"): sizes differ, no sample,
// a number not finite, a wavelength <= 0, wavelengths not strictly increasing.
Spectrum checkedSpectrum(const std::string& source, const std::string& field,
                         std::vector<double> wavelengths_nm, std::vector<double> values);

// Checks the wavelengths of every spectrum of the ingredient (> 0; the
// Spectrum type already guarantees finite, increasing samples) and brings
// each to the unit of its declaration (spectrum_info[key].unit), converting
// the values. Throws InputError(source, field_prefix + ".spectra.<key>...", ...)
// for an unknown unit or one of another dimension.
void normaliseIngredientSpectra(Ingredient& ingredient, const std::string& source,
                                const std::string& field_prefix);

}  // namespace paintlab::db::detail
