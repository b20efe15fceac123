// glTF 2.0 files of a painted object (gltf_format.h).

#include "gltf_format.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/plugins/plugin.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>

namespace paintlab::plugins::gltf {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian, as this host must be");

namespace {

using nlohmann::ordered_json;

constexpr std::uint16_t kPaint = 0;
constexpr std::uint16_t kTyre = 1;
constexpr int kArrayBuffer = 34962;         // bufferView.target of vertex attributes
constexpr int kElementArrayBuffer = 34963;  // of indices
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kTriangles = 4;

void append(std::string& buffer, const void* data, std::size_t bytes) {
    buffer.append(static_cast<const char*>(data), bytes);
}

std::string aspecularName(double aspecular_deg) { return "45as" + io::formatNumber(aspecular_deg); }

ordered_json rounded(double value, double step) { return std::round(value / step) * step; }

ordered_json paintMaterial(const approx::MaterialFit& fit, const Provenance& provenance) {
    const approx::GltfMaterial& m = fit.material;
    ordered_json material;
    material["name"] = provenance.recipe_name.empty() ? "paint" : provenance.recipe_name;
    material["pbrMetallicRoughness"] = {
        {"baseColorFactor", {m.base_color.r, m.base_color.g, m.base_color.b, 1.0}},
        {"metallicFactor", m.metallic},
        {"roughnessFactor", m.roughness}};
    ordered_json extensions;
    extensions["KHR_materials_clearcoat"] = {{"clearcoatFactor", m.clearcoat},
                                             {"clearcoatRoughnessFactor", m.clearcoat_roughness}};
    extensions["KHR_materials_ior"] = {{"ior", m.ior}};
    extensions["KHR_materials_specular"] = {
        {"specularFactor", m.specular},
        {"specularColorFactor", {m.specular_color.r, m.specular_color.g, m.specular_color.b}}};
    if (m.iridescence > 0.0)
        extensions["KHR_materials_iridescence"] = {
            {"iridescenceFactor", m.iridescence},
            {"iridescenceIor", m.iridescence_ior},
            {"iridescenceThicknessMinimum", m.iridescence_thickness_nm},
            {"iridescenceThicknessMaximum", m.iridescence_thickness_nm}};
    material["extensions"] = extensions;
    ordered_json geometries = ordered_json::array();
    for (const approx::GeometryDeltaE& g : fit.geometries)
        geometries.push_back(
            {{"geometry", aspecularName(g.aspecular_deg)},
             {"delta_e00", rounded(g.delta_e00, 0.01)},
             {"reference_lab",
              {rounded(g.reference.L, 0.01), rounded(g.reference.a, 0.01), rounded(g.reference.b, 0.01)}},
             {"approximation_lab",
              {rounded(g.approximation.L, 0.01), rounded(g.approximation.a, 0.01),
               rounded(g.approximation.b, 0.01)}}});
    ordered_json settings = ordered_json::parse(
        provenance.settings_json.empty() ? "{}" : provenance.settings_json, nullptr, false);
    if (settings.is_discarded()) settings = ordered_json::object();
    material["extras"] = {
        {"paintlab",
         {{"recipe", provenance.recipe_path},
          {"fast_model", settings},
          {"approximation",
           "glTF 2.0 material fitted to the fast model's BRDF in linear sRGB (least squares of "
           "ln(1 + f cos_i) at " +
               std::to_string(approx::gltfFitDirections().size()) + " direction pairs)"},
          {"rms_log_residual", fit.rms_log_residual},
          {"conditions", "CIEDE2000 of CIELAB under D65, CIE 1931 2 degree observer"},
          {"max_delta_e00", rounded(fit.max_delta_e00, 0.01)},
          {"mean_delta_e00", rounded(fit.mean_delta_e00, 0.01)},
          {"multiangle", geometries}}}};
    return material;
}

ordered_json tyreMaterial() {
    // The demo scenes' tyre (packaging/demo/scenes/car_body_*.json): glossy black.
    return {
        {"name", "tyre"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.03, 0.03, 0.03, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.35}}}};
}

}  // namespace

raymaps::TriangleMesh objectMesh(std::string_view object) {
    if (object == "sphere") return raymaps::makeIcosphere(0.5, 4, kPaint);
    if (object == "panel") return raymaps::makePlane(0.3, kPaint);
    if (object == "car") return raymaps::makeCarBody(4.2, kPaint, kTyre);
    std::string message = "'";
    message.append(object).append("' is not an object; one of");
    for (std::string_view name : kExportObjects) message.append(" ").append(name);
    throw InputError("<argument>", "object", message);
}

GltfAsset makeAsset(const raymaps::TriangleMesh& mesh, const approx::MaterialFit& fit,
                    const Provenance& provenance) {
    GltfAsset asset;
    ordered_json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "PaintLab glTF exporter (libpaintlab-plugin-gltf)"}};
    ordered_json used = {"KHR_materials_clearcoat", "KHR_materials_ior", "KHR_materials_specular"};
    if (fit.material.iridescence > 0.0) used.push_back("KHR_materials_iridescence");
    doc["extensionsUsed"] = used;
    doc["scene"] = 0;
    doc["scenes"] = {{{"name", provenance.object}, {"nodes", {0}}}};
    doc["nodes"] = {{{"name", provenance.object}, {"mesh", 0}}};
    doc["materials"] = {paintMaterial(fit, provenance)};

    // One primitive per material, each with its own vertices (compacted).
    ordered_json primitives = ordered_json::array();
    ordered_json views = ordered_json::array();
    ordered_json accessors = ordered_json::array();
    bool has_tyre = false;
    for (const std::uint16_t material : {kPaint, kTyre}) {
        std::map<std::uint32_t, std::uint32_t> remap;
        std::vector<std::uint32_t> indices;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            if (mesh.material[t] != material) continue;
            for (const std::uint32_t v : mesh.triangles[t]) {
                const auto [it, inserted] = remap.emplace(v, static_cast<std::uint32_t>(remap.size()));
                indices.push_back(it->second);
            }
        }
        if (indices.empty()) continue;
        if (material == kTyre) has_tyre = true;
        std::vector<float> positions(3 * remap.size());
        std::vector<float> normals(3 * remap.size());
        Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
        Eigen::Vector3f hi = -lo;
        for (const auto& [from, to] : remap) {
            const Eigen::Vector3f p = mesh.positions[from];
            const Eigen::Vector3f n =
                mesh.normals[from].normalized();  // unit in float, as the validator asks
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
            for (std::size_t k = 0; k < 3; ++k) {
                positions[3 * std::size_t{to} + k] = p[static_cast<Eigen::Index>(k)];
                normals[3 * std::size_t{to} + k] = n[static_cast<Eigen::Index>(k)];
            }
        }
        const auto view = [&](const void* data, std::size_t bytes, int target) {
            views.push_back({{"buffer", 0},
                             {"byteOffset", asset.buffer.size()},
                             {"byteLength", bytes},
                             {"target", target}});
            append(asset.buffer, data, bytes);  // every piece is a multiple of 4 bytes: aligned
            return views.size() - 1;
        };
        const std::size_t vertices = remap.size();
        const std::size_t position_view =
            view(positions.data(), positions.size() * sizeof(float), kArrayBuffer);
        const std::size_t normal_view = view(normals.data(), normals.size() * sizeof(float), kArrayBuffer);
        const std::size_t index_view =
            view(indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer);
        accessors.push_back({{"bufferView", position_view},
                             {"componentType", kFloat},
                             {"count", vertices},
                             {"type", "VEC3"},
                             {"min", {lo.x(), lo.y(), lo.z()}},
                             {"max", {hi.x(), hi.y(), hi.z()}}});
        accessors.push_back(
            {{"bufferView", normal_view}, {"componentType", kFloat}, {"count", vertices}, {"type", "VEC3"}});
        accessors.push_back({{"bufferView", index_view},
                             {"componentType", kUnsignedInt},
                             {"count", indices.size()},
                             {"type", "SCALAR"}});
        const std::size_t first = accessors.size() - 3;
        primitives.push_back({{"attributes", {{"POSITION", first}, {"NORMAL", first + 1}}},
                              {"indices", first + 2},
                              {"material", material},
                              {"mode", kTriangles}});
    }
    if (has_tyre) doc["materials"].push_back(tyreMaterial());
    doc["meshes"] = {{{"name", provenance.object}, {"primitives", primitives}}};
    doc["buffers"] = {{{"byteLength", asset.buffer.size()}}};
    doc["bufferViews"] = views;
    doc["accessors"] = accessors;
    asset.json = doc.dump();
    return asset;
}

std::string base64(std::string_view bytes) {
    static constexpr std::string_view kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16U |
                                static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8U |
                                static_cast<unsigned char>(bytes[i + 2]);
        for (int shift = 18; shift >= 0; shift -= 6) out.push_back(kAlphabet[(v >> shift) & 63U]);
    }
    const std::size_t rest = bytes.size() - i;
    if (rest > 0) {
        std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16U;
        if (rest == 2) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8U;
        out.push_back(kAlphabet[(v >> 18U) & 63U]);
        out.push_back(kAlphabet[(v >> 12U) & 63U]);
        out.push_back(rest == 2 ? kAlphabet[(v >> 6U) & 63U] : '=');
        out.push_back('=');
    }
    return out;
}

std::string gltfText(const GltfAsset& asset) {
    ordered_json doc = ordered_json::parse(asset.json);
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(asset.buffer);
    return doc.dump(1) + "\n";
}

std::string glbBytes(const GltfAsset& asset) {
    std::string json = asset.json;
    json.append((4 - json.size() % 4) % 4, ' ');  // chunks are 4-byte aligned: JSON padded with spaces
    std::string bin = asset.buffer;
    bin.append((4 - bin.size() % 4) % 4, '\0');
    const auto word = [](std::string& out, std::uint32_t v) { append(out, &v, sizeof v); };
    std::string out;
    word(out, 0x46546C67U);  // "glTF"
    word(out, 2U);
    word(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    word(out, static_cast<std::uint32_t>(json.size()));
    word(out, 0x4E4F534AU);  // "JSON"
    out += json;
    word(out, static_cast<std::uint32_t>(bin.size()));
    word(out, 0x004E4942U);  // "BIN"
    out += bin;
    return out;
}

}  // namespace paintlab::plugins::gltf
