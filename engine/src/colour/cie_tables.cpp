#include "paintlab/engine/colour/cie_tables.h"

#include "colour/cgats.h"
#include "paintlab/engine/error.h"

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace paintlab {
namespace {

// Where Debian's colord-data package installs its tables.
constexpr const char* kDefaultColordDir = "/usr/share/colord";

// Per (illuminant, observer): the CMF wavelengths used, and the weights
// k S x-bar, k S y-bar, k S z-bar there, k = 1 / sum S y-bar. Integration is
// then a dot product, and the white point the sum of the weights.
struct WeightTable {
    std::vector<double> wavelengths_nm;
    std::vector<double> wx;
    std::vector<double> wy;
    std::vector<double> wz;
    Xyz white;
};

[[noreturn]] void failUnknown(const char* what, int value) {
    throw Error("unknown " + std::string(what) + " " + std::to_string(value));
}

WeightTable buildWeights(Illuminant illuminant, Observer observer) {
    const ColourMatchingFunctions& functions = cmf(observer);
    const Spectrum& power = illuminantSpd(illuminant);
    const std::vector<double>& grid = functions.yBar.wavelengthsNm();
    // Sum only where the illuminant is tabulated: CIE-D50.sp stops at
    // 380-780 nm, and holding its end values constant out to 360 and 830 nm
    // would invent light. D65 and A cover the CMFs' whole 360-830 nm.
    const double first_nm = power.wavelengthsNm().front();
    const double last_nm = power.wavelengthsNm().back();
    WeightTable table;
    double sumX = 0.0;
    double sumY = 0.0;
    double sumZ = 0.0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const double nm = grid[i];
        if (nm < first_nm - 1e-9 || nm > last_nm + 1e-9) continue;
        const double s = power(nm);
        table.wavelengths_nm.push_back(nm);
        table.wx.push_back(s * functions.xBar.values()[i]);
        table.wy.push_back(s * functions.yBar.values()[i]);
        table.wz.push_back(s * functions.zBar.values()[i]);
        sumX += table.wx.back();
        sumY += table.wy.back();
        sumZ += table.wz.back();
    }
    if (table.wavelengths_nm.empty() || !(sumY > 0.0))
        throw Error(illuminantFilePath(illuminant).string() + ": the " + std::string(toString(illuminant)) +
                    " table does not overlap the " + std::string(toString(observer)) + " observer's range");
    const double k = 1.0 / sumY;
    for (std::size_t i = 0; i < table.wy.size(); ++i) {
        table.wx[i] *= k;
        table.wy[i] *= k;
        table.wz[i] *= k;
    }
    // Y = 1 exactly by definition, rather than a sum of weights within a few ulp of it.
    table.white = {sumX / sumY, 1.0, sumZ / sumY};
    return table;
}

// One cached table per combination; each static is built on first use of
// that combination only, so a broken D50 file does not break D65.
template <Illuminant I, Observer O> const WeightTable& cachedWeights() {
    static const WeightTable table = buildWeights(I, O);
    return table;
}

template <Illuminant I> const WeightTable& cachedWeights(Observer observer) {
    switch (observer) {
    case Observer::Cie1931_2deg:
        return cachedWeights<I, Observer::Cie1931_2deg>();
    case Observer::Cie1964_10deg:
        return cachedWeights<I, Observer::Cie1964_10deg>();
    }
    failUnknown("observer", static_cast<int>(observer));
}

const WeightTable& weights(Illuminant illuminant, Observer observer) {
    switch (illuminant) {
    case Illuminant::D65:
        return cachedWeights<Illuminant::D65>(observer);
    case Illuminant::D50:
        return cachedWeights<Illuminant::D50>(observer);
    case Illuminant::A:
        return cachedWeights<Illuminant::A>(observer);
    }
    failUnknown("illuminant", static_cast<int>(illuminant));
}

template <Observer O> const ColourMatchingFunctions& cachedCmf() {
    static const ColourMatchingFunctions table = readCmfFile(cmfFilePath(O));
    return table;
}

template <Illuminant I> const Spectrum& cachedSpd() {
    static const Spectrum table = readSpectrumFile(illuminantFilePath(I));
    return table;
}

}  // namespace

std::string_view toString(Observer observer) noexcept {
    switch (observer) {
    case Observer::Cie1931_2deg:
        return "CIE 1931 2 degree";
    case Observer::Cie1964_10deg:
        return "CIE 1964 10 degree";
    }
    return "unknown observer";
}

std::string_view toString(Illuminant illuminant) noexcept {
    switch (illuminant) {
    case Illuminant::D65:
        return "D65";
    case Illuminant::D50:
        return "D50";
    case Illuminant::A:
        return "A";
    }
    return "unknown illuminant";
}

std::filesystem::path colordDataDir() {
    const char* const overridden = std::getenv("PAINTLAB_COLORD_DIR");
    if (overridden != nullptr && *overridden != '\0') return overridden;
    return kDefaultColordDir;
}

std::filesystem::path cmfFilePath(Observer observer) {
    switch (observer) {
    case Observer::Cie1931_2deg:
        return colordDataDir() / "cmf" / "CIE1931-2deg-XYZ.cmf";
    case Observer::Cie1964_10deg:
        return colordDataDir() / "cmf" / "CIE1964-10deg-XYZ.cmf";
    }
    failUnknown("observer", static_cast<int>(observer));
}

std::filesystem::path illuminantFilePath(Illuminant illuminant) {
    switch (illuminant) {
    case Illuminant::D65:
        return colordDataDir() / "illuminant" / "CIE-D65.sp";
    case Illuminant::D50:
        return colordDataDir() / "illuminant" / "CIE-D50.sp";
    case Illuminant::A:
        return colordDataDir() / "illuminant" / "CIE-A.sp";
    }
    failUnknown("illuminant", static_cast<int>(illuminant));
}

ColourMatchingFunctions readCmfFile(const std::filesystem::path& file) {
    cgats::SpectralTable table = cgats::readSpectralTable(file, 3);
    // Sets in x-bar, y-bar, z-bar order, as colord's cd-it8 writes them.
    return {Spectrum(table.wavelengths_nm, std::move(table.sets[0])),
            Spectrum(table.wavelengths_nm, std::move(table.sets[1])),
            Spectrum(table.wavelengths_nm, std::move(table.sets[2]))};
}

Spectrum readSpectrumFile(const std::filesystem::path& file) {
    cgats::SpectralTable table = cgats::readSpectralTable(file, 1);
    return {std::move(table.wavelengths_nm), std::move(table.sets[0])};
}

const ColourMatchingFunctions& cmf(Observer observer) {
    switch (observer) {
    case Observer::Cie1931_2deg:
        return cachedCmf<Observer::Cie1931_2deg>();
    case Observer::Cie1964_10deg:
        return cachedCmf<Observer::Cie1964_10deg>();
    }
    failUnknown("observer", static_cast<int>(observer));
}

const Spectrum& illuminantSpd(Illuminant illuminant) {
    switch (illuminant) {
    case Illuminant::D65:
        return cachedSpd<Illuminant::D65>();
    case Illuminant::D50:
        return cachedSpd<Illuminant::D50>();
    case Illuminant::A:
        return cachedSpd<Illuminant::A>();
    }
    failUnknown("illuminant", static_cast<int>(illuminant));
}

Xyz whitePoint(Illuminant illuminant, Observer observer) { return weights(illuminant, observer).white; }

Xyz reflectanceToXyz(const Spectrum& reflectance, Illuminant illuminant, Observer observer) {
    const WeightTable& table = weights(illuminant, observer);
    Xyz xyz;
    for (std::size_t i = 0; i < table.wavelengths_nm.size(); ++i) {
        const double r = reflectance(table.wavelengths_nm[i]);
        xyz.X += r * table.wx[i];
        xyz.Y += r * table.wy[i];
        xyz.Z += r * table.wz[i];
    }
    return xyz;
}

}  // namespace paintlab
