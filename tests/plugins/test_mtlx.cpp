// The MaterialX plugin's mapping (plugins/materialx/mtlx_format.h): the glTF
// dielectric's normal reflectance per channel is kept exactly (Fresnel's
// ((n - 1) / (n + 1))^2 at OpenPBR's specular_ior, times its colour), the
// film's thickness changes unit, names are MaterialX names.

#include "mtlx_format.h"

#include <gtest/gtest.h>

#include <cmath>

namespace paintlab::plugins::materialx {
namespace {

double fresnelF0(double n) { return std::pow((n - 1.0) / (n + 1.0), 2.0); }

TEST(Mtlx, KeepsTheDielectricsNormalReflectance) {
    approx::GltfMaterial gltf;
    gltf.ior = 1.5;
    gltf.specular = 0.8;
    gltf.specular_color = {6.0, 2.0, 0.5};  // f0 0.24, 0.08, 0.02 before the factor
    gltf.iridescence = 0.6;
    gltf.iridescence_thickness_nm = 350.0;
    gltf.iridescence_ior = 2.4;
    const OpenPbr s = openPbrFromGltf(gltf);
    const double f0 = fresnelF0(s.specular_ior) * s.specular_weight;
    EXPECT_NEAR(f0 * s.specular_color.r, 0.8 * 0.24, 1e-12);
    EXPECT_NEAR(f0 * s.specular_color.g, 0.8 * 0.08, 1e-12);
    EXPECT_NEAR(f0 * s.specular_color.b, 0.8 * 0.02, 1e-12);
    EXPECT_LE(std::max({s.specular_color.r, s.specular_color.g, s.specular_color.b}),
              1.0);  // OpenPBR's range
    EXPECT_DOUBLE_EQ(s.thin_film_thickness_um, 0.35);
    EXPECT_DOUBLE_EQ(s.thin_film_weight, 0.6);
    EXPECT_DOUBLE_EQ(s.thin_film_ior, 2.4);

    gltf.specular = 0.0;  // no dielectric lobe at all
    EXPECT_EQ(openPbrFromGltf(gltf).specular_weight, 0.0);
}

TEST(Mtlx, NamesAreMaterialXNames) {
    EXPECT_EQ(elementName("Blue pearl (two layers)"), "Blue_pearl__two_layers_");
    EXPECT_EQ(elementName("3-coat"), "paint_3_coat");
    EXPECT_EQ(elementName(""), "paint_");
    EXPECT_EQ(elementName("rouge\xc3\xa9"), "rouge__");
}

TEST(Mtlx, DocumentNamesTheSurfaceItsMaterialUses) {
    approx::MaterialFit fit;
    for (double a : {-15.0, 15.0, 25.0, 45.0, 75.0, 110.0}) fit.geometries.push_back({a, {}, {}, 0.5});
    const std::string x = mtlxText(openPbrFromGltf(fit.material), fit, {"red -- solid", "a--b.json"});
    EXPECT_NE(x.find("<open_pbr_surface name=\"SR_red____solid\" type=\"surfaceshader\">"),
              std::string::npos);
    EXPECT_NE(x.find("nodename=\"SR_red____solid\""), std::string::npos);
    EXPECT_NE(x.find("45as110 0.50"), std::string::npos);
    // A comment never holds "--" (XML 1.0, section 2.5).
    const auto open = x.find("<!--");
    const auto close = x.find("-->", open);
    EXPECT_EQ(x.substr(open + 4, close - open - 4).find("--"), std::string::npos);
}

}  // namespace
}  // namespace paintlab::plugins::materialx
