// The glTF plugin's format (plugins/gltf/gltf_format.h): the meshes of the
// three objects, the document's accessors against the buffer they describe,
// base64 (RFC 4648's test vectors), the .glb container, bad object names.
// That the files pass the Khronos validator is tests/plugins/gltf_validate.sh.

#include "gltf_format.h"

#include "paintlab/engine/error.h"
#include "paintlab/plugins/plugin.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace paintlab::plugins::gltf {
namespace {

approx::MaterialFit someFit(bool iridescence) {
    approx::MaterialFit fit;
    fit.material.base_color = {0.5, 0.1, 0.1};
    fit.material.clearcoat = 0.96;
    fit.material.iridescence = iridescence ? 0.7 : 0.0;
    for (double a : {-15.0, 15.0, 25.0, 45.0, 75.0, 110.0}) {
        approx::GeometryDeltaE g;
        g.aspecular_deg = a;
        g.delta_e00 = 0.5 + a / 100.0;
        fit.geometries.push_back(g);
    }
    fit.max_delta_e00 = 1.6;
    return fit;
}

TEST(Gltf, Base64MatchesTheRfcVectors) {
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foob"), "Zm9vYg==");
    EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(Gltf, ObjectsHaveUnitNormalsAndValidTriangles) {
    for (std::string_view name : kExportObjects) {
        const raymaps::TriangleMesh mesh = objectMesh(name);
        ASSERT_FALSE(mesh.triangles.empty()) << name;
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << name;
        for (const auto& n : mesh.normals) EXPECT_NEAR(n.norm(), 1.0F, 1e-5F) << name;
        for (const auto& t : mesh.triangles)
            for (std::uint32_t v : t) ASSERT_LT(v, mesh.positions.size()) << name;
    }
    EXPECT_THROW(objectMesh("cube"), InputError);
}

TEST(Gltf, AccessorsDescribeTheBuffer) {
    const raymaps::TriangleMesh mesh = objectMesh("car");
    const GltfAsset asset = makeAsset(mesh, someFit(true), {"red", "red.json", "{}", "car"});
    const auto doc = nlohmann::json::parse(asset.json);
    ASSERT_EQ(doc["meshes"][0]["primitives"].size(), 2U);  // paint and tyres
    EXPECT_EQ(doc["materials"].size(), 2U);
    EXPECT_EQ(doc["buffers"][0]["byteLength"].get<std::size_t>(), asset.buffer.size());
    std::size_t triangles = 0;
    for (const auto& primitive : doc["meshes"][0]["primitives"]) {
        const auto& position = doc["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()];
        const auto& normal = doc["accessors"][primitive["attributes"]["NORMAL"].get<std::size_t>()];
        const auto& index = doc["accessors"][primitive["indices"].get<std::size_t>()];
        const auto count = position["count"].get<std::size_t>();
        ASSERT_EQ(normal["count"].get<std::size_t>(), count);
        const auto& pv = doc["bufferViews"][position["bufferView"].get<std::size_t>()];
        const auto& nv = doc["bufferViews"][normal["bufferView"].get<std::size_t>()];
        const auto& iv = doc["bufferViews"][index["bufferView"].get<std::size_t>()];
        ASSERT_EQ(pv["byteLength"].get<std::size_t>(), count * 12);
        ASSERT_LE(iv["byteOffset"].get<std::size_t>() + iv["byteLength"].get<std::size_t>(),
                  asset.buffer.size());
        // Every position inside min..max, every min and max reached; normals unit; indices in range.
        std::array<float, 3> lo{1e30F, 1e30F, 1e30F};
        std::array<float, 3> hi{-1e30F, -1e30F, -1e30F};
        for (std::size_t v = 0; v < count; ++v) {
            std::array<float, 3> p{};
            std::array<float, 3> n{};
            std::memcpy(p.data(), asset.buffer.data() + pv["byteOffset"].get<std::size_t>() + 12 * v, 12);
            std::memcpy(n.data(), asset.buffer.data() + nv["byteOffset"].get<std::size_t>() + 12 * v, 12);
            for (std::size_t k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], p[k]);
                hi[k] = std::max(hi[k], p[k]);
            }
            EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0F, 1e-6F);
        }
        for (std::size_t k = 0; k < 3; ++k) {
            EXPECT_EQ(position["min"][k].get<float>(), lo[k]);
            EXPECT_EQ(position["max"][k].get<float>(), hi[k]);
        }
        const auto indices = index["count"].get<std::size_t>();
        ASSERT_EQ(indices % 3, 0U);
        triangles += indices / 3;
        for (std::size_t i = 0; i < indices; ++i) {
            std::uint32_t value = 0;
            std::memcpy(&value, asset.buffer.data() + iv["byteOffset"].get<std::size_t>() + 4 * i, 4);
            ASSERT_LT(value, count);
        }
    }
    EXPECT_EQ(triangles, mesh.triangles.size());
    // The material carries the approximation's ΔE00 per geometry.
    const auto& extras = doc["materials"][0]["extras"]["paintlab"];
    ASSERT_EQ(extras["multiangle"].size(), 6U);
    EXPECT_EQ(extras["multiangle"][5]["geometry"], "45as110");
    EXPECT_DOUBLE_EQ(extras["multiangle"][5]["delta_e00"].get<double>(), 1.6);
    EXPECT_TRUE(doc["materials"][0]["extensions"].contains("KHR_materials_iridescence"));
}

TEST(Gltf, GlbChunksAreAlignedAndSized) {
    const GltfAsset asset = makeAsset(objectMesh("panel"), someFit(false), {"red", "", "{}", "panel"});
    const std::string glb = glbBytes(asset);
    std::array<std::uint32_t, 5> head{};
    std::memcpy(head.data(), glb.data(), sizeof head);
    EXPECT_EQ(head[0], 0x46546C67U);  // "glTF"
    EXPECT_EQ(head[1], 2U);
    EXPECT_EQ(head[2], glb.size());
    EXPECT_EQ(head[3] % 4, 0U);
    EXPECT_EQ(head[4], 0x4E4F534AU);  // "JSON"
    std::array<std::uint32_t, 2> bin{};
    std::memcpy(bin.data(), glb.data() + 20 + head[3], sizeof bin);
    EXPECT_EQ(bin[1], 0x004E4942U);  // "BIN"
    EXPECT_EQ(20 + head[3] + 8 + bin[0], glb.size());
    EXPECT_GE(bin[0], asset.buffer.size());
    const auto json = nlohmann::json::parse(glb.substr(20, head[3]));
    EXPECT_FALSE(json["buffers"][0].contains("uri"));  // the BIN chunk
    EXPECT_FALSE(json["materials"][0]["extensions"].contains("KHR_materials_iridescence"));
    const auto text = nlohmann::json::parse(gltfText(asset));
    EXPECT_EQ(text["buffers"][0]["uri"].get<std::string>().rfind("data:application/octet-stream;base64,", 0),
              0U);
}

}  // namespace
}  // namespace paintlab::plugins::gltf
