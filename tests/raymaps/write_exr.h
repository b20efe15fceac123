#pragma once
// A float RGB EXR written for a test (a lat-long environment): one helper
// for the ray-map tests that make their own HDR.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

namespace paintlab::test {

// rgb: width x height x 3 floats, row-major, top row first. Returns `path`.
inline std::filesystem::path writeExr(const std::filesystem::path& path, int width, int height,
                                      const std::vector<float>& rgb) {
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out && out->open(path.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    out->close();
    return path;
}

}  // namespace paintlab::test
