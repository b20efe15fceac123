// MaterialX documents with an OpenPBR surface (mtlx_format.h).

#include "mtlx_format.h"

#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace paintlab::plugins::materialx {

namespace {

std::string number(double value) { return io::formatNumber(value, io::NumberFormat::Message); }

std::string colour(const Rgb& c) { return number(c.r) + ", " + number(c.g) + ", " + number(c.b); }

// Text inside an XML comment: no "--", printable ASCII and UTF-8 bytes only.
std::string commentText(std::string_view text) {
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        const char kept = (u < 0x20 || u == 0x7F) ? ' ' : c;
        if (kept == '-' && !out.empty() && out.back() == '-') out.push_back(' ');
        out.push_back(kept);
    }
    if (!out.empty() && out.back() == '-') out.push_back(' ');
    return out;
}

}  // namespace

OpenPbr openPbrFromGltf(const approx::GltfMaterial& gltf) {
    OpenPbr s;
    s.base_color = gltf.base_color;
    s.base_metalness = gltf.metallic;
    s.specular_roughness = gltf.roughness;
    // glTF's dielectric normal reflectance per channel (KHR_materials_specular, _ior).
    const double f0_ior = std::pow((gltf.ior - 1.0) / (gltf.ior + 1.0), 2.0);
    const Rgb f0{gltf.specular * std::min(f0_ior * gltf.specular_color.r, 1.0),
                 gltf.specular * std::min(f0_ior * gltf.specular_color.g, 1.0),
                 gltf.specular * std::min(f0_ior * gltf.specular_color.b, 1.0)};
    const double largest = std::max({f0.r, f0.g, f0.b});
    if (largest > 0.0) {
        // The index whose normal reflectance is the largest channel (below 1).
        const double root = std::sqrt(std::min(largest, 0.9999));
        s.specular_ior = (1.0 + root) / (1.0 - root);
        s.specular_color = {f0.r / largest, f0.g / largest, f0.b / largest};
        s.specular_weight = 1.0;
    } else {
        s.specular_weight = 0.0;
        s.specular_ior = gltf.ior;
    }
    s.coat_weight = gltf.clearcoat;
    s.coat_roughness = gltf.clearcoat_roughness;
    s.coat_ior = 1.5;
    s.coat_darkening = 0.0;
    s.thin_film_weight = gltf.iridescence;
    s.thin_film_thickness_um = gltf.iridescence_thickness_nm / 1000.0;
    s.thin_film_ior = gltf.iridescence_ior;
    return s;
}

std::string elementName(std::string_view text) {
    std::string out;
    for (const char c : text)
        out.push_back(std::isalnum(static_cast<unsigned char>(c)) != 0 && static_cast<unsigned char>(c) < 0x80
                          ? c
                          : '_');
    if (out.empty() || std::isdigit(static_cast<unsigned char>(out.front())) != 0) out.insert(0, "paint_");
    return out;
}

std::string mtlxText(const OpenPbr& s, const approx::MaterialFit& fit, const Provenance& provenance) {
    const std::string name = elementName(provenance.recipe_name.empty() ? "paint" : provenance.recipe_name);
    const std::string report = approx::deltaESummary(fit, kModelName);

    std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    x += "<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n";
    x += "  <!-- PaintLab recipe " + commentText(provenance.recipe_name) + " (" +
         commentText(provenance.recipe_path) + ") -->\n";
    x += "  <!-- " + commentText(report) + " (CIELAB D65, 2 degree observer) -->\n";
    x += "  <open_pbr_surface name=\"SR_" + name + "\" type=\"surfaceshader\">\n";
    const auto input = [&x](const char* input_name, const char* type, const std::string& value) {
        x += std::string("    <input name=\"") + input_name + "\" type=\"" + type + "\" value=\"" + value +
             "\" />\n";
    };
    input("base_weight", "float", number(s.base_weight));
    input("base_color", "color3", colour(s.base_color));
    input("base_metalness", "float", number(s.base_metalness));
    input("base_diffuse_roughness", "float", number(s.base_diffuse_roughness));
    input("specular_weight", "float", number(s.specular_weight));
    input("specular_color", "color3", colour(s.specular_color));
    input("specular_roughness", "float", number(s.specular_roughness));
    input("specular_ior", "float", number(s.specular_ior));
    input("coat_weight", "float", number(s.coat_weight));
    input("coat_roughness", "float", number(s.coat_roughness));
    input("coat_ior", "float", number(s.coat_ior));
    input("coat_darkening", "float", number(s.coat_darkening));
    input("thin_film_weight", "float", number(s.thin_film_weight));
    input("thin_film_thickness", "float", number(s.thin_film_thickness_um));
    input("thin_film_ior", "float", number(s.thin_film_ior));
    x += "  </open_pbr_surface>\n";
    x += R"(  <surfacematerial name="M_)" + name + R"(" type="material" doc=")" + report + "\">\n";
    x += R"(    <input name="surfaceshader" type="surfaceshader" nodename="SR_)" + name + "\" />\n";
    x += "  </surfacematerial>\n";
    x += "</materialx>\n";
    return x;
}

}  // namespace paintlab::plugins::materialx
