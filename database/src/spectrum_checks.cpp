// Imported spectra: sample checks and unit conversion (spectrum_checks.h).

#include "spectrum_checks.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"

#include <cmath>

namespace paintlab::db::detail {

namespace {

using io::formatNumber;

// Visits every spectrum of an engine struct with its declaration, mutably.
template <class F> struct SpectrumVisitor {
    F f;
    void scalar(const ParameterDecl& /*decl*/, double& /*value*/) {}
    void spectrum(const ParameterDecl& decl, Spectrum& spectrum) { f(decl, spectrum); }
    void optionalSpectrum(const ParameterDecl& decl, std::optional<Spectrum>& spectrum) {
        if (spectrum) f(decl, *spectrum);
    }
};

template <class F> void forEachSpectrum(IngredientData& data, F f) {
    SpectrumVisitor<F> visitor{std::move(f)};
    std::visit(
        [&](auto& d) {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, Substrate>)
                std::visit([&](auto& s) { std::decay_t<decltype(s)>::traverse(s, visitor); }, d);
            else
                T::traverse(d, visitor);
        },
        data);
}

}  // namespace

std::optional<UnitConversion> canonicalUnit(std::string_view unit) {
    struct Known {
        std::string_view text;
        std::string_view canonical;
        double factor;
    };
    static constexpr Known kKnown[] = {
        {"1", "1", 1.0},        {"%", "1", 0.01},       {"1/nm", "1/µm", 1e3}, {"1/µm", "1/µm", 1.0},
        {"1/um", "1/µm", 1.0},  {"1/μm", "1/µm", 1.0},  // U+03BC mu
        {"1/mm", "1/µm", 1e-3}, {"1/cm", "1/µm", 1e-4}, {"1/m", "1/µm", 1e-6}, {"1/sr", "1/sr", 1.0},
    };
    for (const auto& known : kKnown)
        if (known.text == unit) return UnitConversion{std::string(known.canonical), known.factor};
    return std::nullopt;
}

Spectrum checkedSpectrum(const std::string& source, const std::string& field,
                         std::vector<double> wavelengths_nm, std::vector<double> values) {
    if (wavelengths_nm.size() != values.size())
        throw InputError(source, field,
                         std::to_string(wavelengths_nm.size()) + " wavelengths but " +
                             std::to_string(values.size()) + " values");
    if (values.empty()) throw InputError(source, field, "no sample");
    const auto at = [&field](const char* what, std::size_t i) {
        std::string out = field;
        out.append(what).append("[").append(std::to_string(i)).append("]");
        return out;
    };
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(wavelengths_nm[i]))
            throw InputError(source, at(".wavelengths_nm", i), "not a finite number");
        if (!std::isfinite(values[i])) throw InputError(source, at(".values", i), "not a finite number");
        if (wavelengths_nm[i] <= 0.0)
            throw InputError(source, at(".wavelengths_nm", i),
                             formatNumber(wavelengths_nm[i]) + " nm: a wavelength must be positive");
        if (i > 0 && wavelengths_nm[i] <= wavelengths_nm[i - 1])
            throw InputError(source, at(".wavelengths_nm", i),
                             formatNumber(wavelengths_nm[i]) + " nm does not increase on the previous " +
                                 formatNumber(wavelengths_nm[i - 1]) +
                                 " nm (wavelengths must be strictly increasing)");
    }
    return {std::move(wavelengths_nm), std::move(values)};
}

void normaliseIngredientSpectra(Ingredient& ingredient, const std::string& source,
                                const std::string& field_prefix) {
    forEachSpectrum(ingredient.data, [&](const ParameterDecl& decl, Spectrum& spectrum) {
        const std::string key(decl.key);
        const std::string field = field_prefix + ".spectra." + key;
        if (!spectrum.isConstant()) {
            const auto& wavelengths = spectrum.wavelengthsNm();
            for (std::size_t i = 0; i < wavelengths.size(); ++i)
                if (wavelengths[i] <= 0.0)
                    throw InputError(source, field + ".wavelengths_nm[" + std::to_string(i) + "]",
                                     formatNumber(wavelengths[i]) + " nm: a wavelength must be positive");
        }
        auto found = ingredient.spectrum_info.find(key);
        if (found == ingredient.spectrum_info.end()) return;  // stored with the declared unit
        const auto conversion = canonicalUnit(found->second.unit);
        if (!conversion)
            throw InputError(source, field + ".unit",
                             "unknown unit '" + found->second.unit + "' (this field is in " +
                                 std::string(decl.unit) + ")");
        if (conversion->unit != decl.unit)
            throw InputError(source, field + ".unit",
                             "unit '" + found->second.unit + "' does not fit this field, which is in " +
                                 std::string(decl.unit));
        found->second.unit = conversion->unit;
        if (conversion->factor == 1.0) return;
        std::vector<double> values = spectrum.values();
        for (double& v : values) v *= conversion->factor;
        spectrum = spectrum.isConstant() ? Spectrum(values.front())
                                         : Spectrum(spectrum.wavelengthsNm(), std::move(values));
    });
}

}  // namespace paintlab::db::detail
