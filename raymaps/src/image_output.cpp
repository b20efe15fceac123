// Writing relit images: linear EXR, tone-mapped sRGB PNG (OpenImageIO),
// encoded in memory and then written with the one atomic file writer.

#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/raymaps/display_image.h"
#include "paintlab/raymaps/relight.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

namespace paintlab::raymaps {

namespace {

// Extended Reinhard (Reinhard et al. 2002, eq. 4) per channel: 1 maps to
// about 0.53, the white point to 1, so highlights keep some gradation.
double toneMap(double x) {
    constexpr double kWhite = 4.0;
    return x * (1.0 + x / (kWhite * kWhite)) / (1.0 + x);
}

}  // namespace

std::vector<std::uint8_t> toDisplayRgb8(const RgbImage& image, double exposure_ev) {
    const double scale = std::exp2(exposure_ev);
    std::vector<std::uint8_t> bytes(image.rgb.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const double x = std::max(0.0, static_cast<double>(image.rgb[i]) * scale);
        const double encoded = srgbEncode(std::min(1.0, toneMap(x)));
        bytes[i] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(encoded, 0.0, 1.0)));
    }
    return bytes;
}

void writeImage(const RgbImage& image, const std::filesystem::path& path, double exposure_ev) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const bool png = ext == ".png";
    if (!png && ext != ".exr")
        throw InputError("<argument>", "--out", path.string() + ": the image must be .exr (linear) or .png");
    const std::string name = path.string();
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create(name, &memory);
    if (!out) throw Error(name + ": cannot create an image writer: " + OIIO::geterror());
    const double scale = std::exp2(exposure_ev);
    const std::size_t n = image.rgb.size();
    OIIO::ImageSpec spec(image.width, image.height, 3, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    if (!out->open(name, spec)) throw Error(name + ": cannot open for writing: " + out->geterror());
    bool ok = false;
    if (png) {
        const std::vector<std::uint8_t> bytes = toDisplayRgb8(image, exposure_ev);
        ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    } else {
        std::vector<float> scaled(n);
        for (std::size_t i = 0; i < n; ++i)
            scaled[i] = static_cast<float>(static_cast<double>(image.rgb[i]) * scale);
        ok = out->write_image(OIIO::TypeDesc::FLOAT, scaled.data());
    }
    if (!ok || !out->close()) throw Error(name + ": cannot write the image: " + out->geterror());
    out.reset();
    io::writeFileAtomically(path,
                            std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

}  // namespace paintlab::raymaps
