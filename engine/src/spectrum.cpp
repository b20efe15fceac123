#include "paintlab/engine/spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace paintlab {

std::vector<double> uniformWavelengthGrid(double first_nm, double last_nm, double step_nm) {
    if (!(step_nm > 0.0) || !(last_nm >= first_nm))
        throw std::invalid_argument("wavelength grid needs step > 0 and last >= first");
    // Round so that 380..780 step 10 gives exactly 41 samples despite floating point.
    const auto count = static_cast<std::size_t>(std::floor((last_nm - first_nm) / step_nm + 1e-9)) + 1;
    std::vector<double> grid(count);
    for (std::size_t i = 0; i < count; ++i) grid[i] = first_nm + static_cast<double>(i) * step_nm;
    return grid;
}

std::vector<double> visibleBands(std::size_t band_count) {
    if (band_count < 2) throw std::invalid_argument("visibleBands needs at least 2 bands");
    std::vector<double> grid(band_count);
    const double step = (kVisibleMaxNm - kVisibleMinNm) / static_cast<double>(band_count - 1);
    for (std::size_t i = 0; i < band_count; ++i) grid[i] = kVisibleMinNm + static_cast<double>(i) * step;
    return grid;
}

Spectrum::Spectrum(double value) : m_wavelengths_nm{kVisibleMinNm}, m_values{value} {
    if (!std::isfinite(value)) throw std::invalid_argument("spectrum value is not finite");
}

Spectrum::Spectrum(std::vector<double> wavelengths_nm, std::vector<double> values)
    : m_wavelengths_nm(std::move(wavelengths_nm)), m_values(std::move(values)) {
    if (m_values.empty()) throw std::invalid_argument("spectrum has no samples");
    if (m_values.size() != m_wavelengths_nm.size())
        throw std::invalid_argument("spectrum has " + std::to_string(m_wavelengths_nm.size()) +
                                    " wavelengths but " + std::to_string(m_values.size()) + " values");
    for (std::size_t i = 0; i < m_values.size(); ++i) {
        if (!std::isfinite(m_wavelengths_nm[i]) || !std::isfinite(m_values[i]))
            throw std::invalid_argument("spectrum sample " + std::to_string(i) + " is not finite");
        if (i > 0 && !(m_wavelengths_nm[i] > m_wavelengths_nm[i - 1]))
            throw std::invalid_argument("spectrum wavelengths are not strictly increasing at sample " +
                                        std::to_string(i));
    }
}

double Spectrum::operator()(double wavelength_nm) const {
    if (m_values.size() == 1 || wavelength_nm <= m_wavelengths_nm.front()) return m_values.front();
    if (wavelength_nm >= m_wavelengths_nm.back()) return m_values.back();
    const auto upper = std::upper_bound(m_wavelengths_nm.begin(), m_wavelengths_nm.end(), wavelength_nm);
    const auto i = static_cast<std::size_t>(upper - m_wavelengths_nm.begin());
    const double x0 = m_wavelengths_nm[i - 1];
    const double x1 = m_wavelengths_nm[i];
    const double t = (wavelength_nm - x0) / (x1 - x0);
    return m_values[i - 1] + t * (m_values[i] - m_values[i - 1]);
}

std::vector<double> Spectrum::sample(std::span<const double> wavelengths_nm) const {
    std::vector<double> out(wavelengths_nm.size());
    std::transform(wavelengths_nm.begin(), wavelengths_nm.end(), out.begin(),
                   [this](double nm) { return (*this)(nm); });
    return out;
}

Spectrum Spectrum::resampled(std::span<const double> wavelengths_nm) const {
    return {std::vector<double>(wavelengths_nm.begin(), wavelengths_nm.end()), sample(wavelengths_nm)};
}

double Spectrum::minValue() const noexcept { return *std::min_element(m_values.begin(), m_values.end()); }
double Spectrum::maxValue() const noexcept { return *std::max_element(m_values.begin(), m_values.end()); }

}  // namespace paintlab
