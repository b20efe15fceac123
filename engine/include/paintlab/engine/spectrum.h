#pragma once
// Spectra on a wavelength grid: a tabulated function of wavelength (nm),
// piecewise linear between samples and held constant beyond the ends, which
// is how measured optical constants and instrument spectra are meant.
// A constant spectrum is stored as a single sample.

#include <cstddef>
#include <span>
#include <vector>

namespace paintlab {

// The visible range PaintLab computes over (shared/ARCHITECTURE.md, "The fast model").
inline constexpr double kVisibleMinNm = 380.0;
inline constexpr double kVisibleMaxNm = 780.0;

// Uniform grid from first_nm to last_nm inclusive with the given step.
// Throws std::invalid_argument if step_nm <= 0 or last_nm < first_nm.
std::vector<double> uniformWavelengthGrid(double first_nm, double last_nm, double step_nm);

// band_count band centres covering [kVisibleMinNm, kVisibleMaxNm] evenly
// (band_count = 41 gives 380, 390, ..., 780). Throws std::invalid_argument if band_count < 2.
std::vector<double> visibleBands(std::size_t band_count);

class Spectrum {
public:
    Spectrum() : Spectrum(0.0) {}
    // A spectrum equal to value at every wavelength.
    explicit Spectrum(double value);
    // Throws std::invalid_argument if the sizes differ, there is no sample,
    // wavelengths are not strictly increasing, or any number is not finite.
    Spectrum(std::vector<double> wavelengths_nm, std::vector<double> values);

    double operator()(double wavelength_nm) const;
    // The same function sampled on another grid (linear interpolation, ends held).
    Spectrum resampled(std::span<const double> wavelengths_nm) const;
    // Values at the given wavelengths, without building a Spectrum.
    std::vector<double> sample(std::span<const double> wavelengths_nm) const;

    bool isConstant() const noexcept { return m_values.size() == 1; }
    const std::vector<double>& wavelengthsNm() const noexcept { return m_wavelengths_nm; }
    const std::vector<double>& values() const noexcept { return m_values; }
    double minValue() const noexcept;
    double maxValue() const noexcept;

    friend bool operator==(const Spectrum&, const Spectrum&) = default;

private:
    std::vector<double> m_wavelengths_nm;  // strictly increasing; one entry (ignored) if constant
    std::vector<double> m_values;
};

}  // namespace paintlab
