#include "paintlab/engine/recipe_json.h"

#include "json_reader.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/recipe_validation.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace paintlab {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

using jsonio::typeName;

// The generic field reader plus what the recipe's traversal hooks (recipe.h)
// call: scalars, spectra (a number or a table) and optional spectra.
class ObjectReader : public jsonio::ObjectReader {
public:
    using jsonio::ObjectReader::number;
    using jsonio::ObjectReader::ObjectReader;

    Spectrum spectrumValue(std::string_view key, const json& value) const {
        if (value.is_number()) return Spectrum(number(key, value));
        if (!value.is_object())
            fail(key, R"(expected a number or {"wavelengths_nm": [...], "values": [...]}, found )" +
                          typeName(value));
        jsonio::ObjectReader table(value, fieldPath(key), source());
        auto wavelengths =
            table.numberArray("wavelengths_nm", table.require("wavelengths_nm", "wavelengths in nm"));
        auto values = table.numberArray("values", table.require("values", "one value per wavelength"));
        table.finish();
        try {
            return {std::move(wavelengths), std::move(values)};
        } catch (const std::invalid_argument& e) {
            fail(key, e.what());
        }
    }

    // The traversal hook's visitor interface (recipe.h).
    void scalar(const ParameterDecl& decl, double& out) {
        const json* value = decl.required ? &require(decl.key, decl.label) : find(decl.key);
        out = value == nullptr ? decl.defaultValue : number(decl.key, *value);
    }
    void spectrum(const ParameterDecl& decl, Spectrum& out) {
        const json* value = decl.required ? &require(decl.key, decl.label) : find(decl.key);
        out = value == nullptr ? Spectrum(decl.defaultValue) : spectrumValue(decl.key, *value);
    }
    void optionalSpectrum(const ParameterDecl& decl, std::optional<Spectrum>& out) {
        const json* value = find(decl.key);
        if (value == nullptr)
            out.reset();
        else
            out = spectrumValue(decl.key, *value);
    }
};

std::optional<DepthProfile> readDepthProfile(ObjectReader& owner, const std::string& source) {
    const json* value = owner.find("depth_profile");
    if (value == nullptr) return std::nullopt;
    ObjectReader reader(*value, owner.fieldPath("depth_profile"), source);
    DepthProfile profile;
    profile.depth =
        reader.numberArray("depth", reader.require("depth", "relative depths, 0 = top, 1 = bottom"));
    profile.weight =
        reader.numberArray("weight", reader.require("weight", "relative concentration at each depth"));
    reader.finish();
    if (profile.depth.size() != profile.weight.size())
        reader.fail("weight", "has " + std::to_string(profile.weight.size()) + " entries but depth has " +
                                  std::to_string(profile.depth.size()));
    return profile;
}

template <class T> T readComponentFields(ObjectReader& reader, const std::string& source) {
    T component;
    component.name = reader.string("name", true);
    component.source = reader.string("source", false);
    T::traverse(component, reader);
    if constexpr (requires { component.depth_profile; })
        component.depth_profile = readDepthProfile(reader, source);
    return component;
}

Component readComponent(const json& value, const std::string& path, const std::string& source) {
    ObjectReader reader(value, path, source);
    const std::string kind = reader.string("kind", true);
    Component component;
    if (kind == Pigment::kKind)
        component = readComponentFields<Pigment>(reader, source);
    else if (kind == MirrorFlake::kKind)
        component = readComponentFields<MirrorFlake>(reader, source);
    else if (kind == InterferenceFlake::kKind)
        component = readComponentFields<InterferenceFlake>(reader, source);
    else if (kind == RawMedium::kKind)
        component = readComponentFields<RawMedium>(reader, source);
    else
        reader.fail("kind", "unknown component kind '" + kind +
                                "' (expected pigment, mirror_flake, interference_flake or raw_medium)");
    reader.finish();
    return component;
}

Layer readLayer(const json& value, const std::string& path, const std::string& source) {
    ObjectReader reader(value, path, source);
    Layer layer;
    layer.name = reader.string("name", true);
    Layer::traverse(layer, reader);
    if (const json* binder = reader.find("binder")) {
        ObjectReader binder_reader(*binder, reader.fieldPath("binder"), source);
        layer.binder.name = binder_reader.string("name", false);
        Binder::traverse(layer.binder, binder_reader);
        binder_reader.finish();
    }
    if (const json* components = reader.find("components")) {
        if (!components->is_array())
            reader.fail("components", "expected an array, found " + typeName(*components));
        for (std::size_t i = 0; i < components->size(); ++i)
            layer.components.push_back(
                readComponent((*components)[i], reader.elementPath("components", i), source));
    }
    reader.finish();
    return layer;
}

template <class T> Substrate readSubstrateFields(ObjectReader& reader) {
    T substrate;
    T::traverse(substrate, reader);
    return substrate;
}

Substrate readSubstrate(const json& value, const std::string& source) {
    ObjectReader reader(value, "substrate", source);
    const std::string kind = reader.string("kind", true);
    Substrate substrate;
    if (kind == LambertianSubstrate::kKind)
        substrate = readSubstrateFields<LambertianSubstrate>(reader);
    else if (kind == MetalSubstrate::kKind)
        substrate = readSubstrateFields<MetalSubstrate>(reader);
    else if (kind == BlackSubstrate::kKind)
        substrate = readSubstrateFields<BlackSubstrate>(reader);
    else if (kind == TransparentSubstrate::kKind)
        substrate = readSubstrateFields<TransparentSubstrate>(reader);
    else
        reader.fail("kind", "unknown substrate kind '" + kind +
                                "' (expected lambertian, metal, black or transparent)");
    reader.finish();
    return substrate;
}

// Writes fields in declaration order; every field, defaults included, so the
// file says exactly what was simulated.
class ObjectWriter {
public:
    explicit ObjectWriter(ordered_json& out) : m_out(out) {}

    static ordered_json spectrumJson(const Spectrum& s) {
        if (s.isConstant()) return s.values().front();
        ordered_json table;
        table["wavelengths_nm"] = s.wavelengthsNm();
        table["values"] = s.values();
        return table;
    }
    void scalar(const ParameterDecl& decl, const double& value) { m_out[std::string(decl.key)] = value; }
    void spectrum(const ParameterDecl& decl, const Spectrum& value) {
        m_out[std::string(decl.key)] = spectrumJson(value);
    }
    void optionalSpectrum(const ParameterDecl& decl, const std::optional<Spectrum>& value) {
        if (value) spectrum(decl, *value);
    }

private:
    ordered_json& m_out;
};

ordered_json componentJson(const Component& component) {
    ordered_json out;
    std::visit(
        [&out](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            out["kind"] = std::string(T::kKind);
            out["name"] = c.name;
            if (!c.source.empty()) out["source"] = c.source;
            ObjectWriter writer(out);
            T::traverse(c, writer);
            if constexpr (requires { c.depth_profile; }) {
                if (c.depth_profile)
                    out["depth_profile"] = {{"depth", c.depth_profile->depth},
                                            {"weight", c.depth_profile->weight}};
            }
        },
        component);
    return out;
}

ordered_json layerJson(const Layer& layer) {
    ordered_json out;
    out["name"] = layer.name;
    ObjectWriter writer(out);
    Layer::traverse(layer, writer);
    ordered_json binder;
    if (!layer.binder.name.empty()) binder["name"] = layer.binder.name;
    ObjectWriter binder_writer(binder);
    Binder::traverse(layer.binder, binder_writer);
    out["binder"] = binder;
    out["components"] = ordered_json::array();
    for (const auto& c : layer.components) out["components"].push_back(componentJson(c));
    return out;
}

ordered_json substrateJson(const Substrate& substrate) {
    ordered_json out;
    std::visit(
        [&out](const auto& s) {
            using T = std::decay_t<decltype(s)>;
            out["kind"] = std::string(T::kKind);
            ObjectWriter writer(out);
            T::traverse(s, writer);
        },
        substrate);
    return out;
}

}  // namespace

Recipe parseRecipeJson(std::string_view text, const std::string& source) {
    const json document = jsonio::parseUntrustedJson(text, source);
    ObjectReader reader(document, "", source);

    const json& version = reader.require("schema_version", "recipe format version");
    if (!version.is_number_integer())
        reader.fail("schema_version", "expected an integer, found " + typeName(version));
    if (version.get<long long>() != Recipe::kSchemaVersion)
        reader.fail("schema_version", "unsupported schema version " + version.dump() +
                                          " (this PaintLab reads version " +
                                          std::to_string(Recipe::kSchemaVersion) + ")");

    Recipe recipe;
    recipe.name = reader.string("name", true);
    recipe.description = reader.string("description", false);
    if (const json* ambient = reader.find("ambient")) {
        ObjectReader ambient_reader(*ambient, "ambient", source);
        ambient_reader.scalar(params::kAmbientIndex, recipe.ambient_refractive_index);
        ambient_reader.finish();
    }
    const json& layers = reader.require("layers", "the layers, top first");
    if (!layers.is_array()) reader.fail("layers", "expected an array of layers, found " + typeName(layers));
    for (std::size_t i = 0; i < layers.size(); ++i)
        recipe.layers.push_back(readLayer(layers[i], reader.elementPath("layers", i), source));
    recipe.substrate = readSubstrate(reader.require("substrate", "what the paint is applied on"), source);
    reader.finish();
    return recipe;
}

Recipe parseRecipeFile(const std::filesystem::path& path) {
    return parseRecipeJson(jsonio::readBoundedTextFile(path, kMaxRecipeFileBytes), path.string());
}

Recipe loadRecipeFile(const std::filesystem::path& path) {
    Recipe recipe = parseRecipeFile(path);
    validateRecipe(recipe, path.string());
    return recipe;
}

std::string recipeToJson(const Recipe& recipe) {
    ordered_json out;
    out["schema_version"] = Recipe::kSchemaVersion;
    out["name"] = recipe.name;
    if (!recipe.description.empty()) out["description"] = recipe.description;
    out["ambient"] = {{std::string(params::kAmbientIndex.key), recipe.ambient_refractive_index}};
    out["layers"] = ordered_json::array();
    for (const auto& layer : recipe.layers) out["layers"].push_back(layerJson(layer));
    out["substrate"] = substrateJson(recipe.substrate);
    return out.dump(2) + "\n";
}

void saveRecipeFile(const Recipe& recipe, const std::filesystem::path& path) {
    io::writeFileAtomically(path, recipeToJson(recipe));
}

}  // namespace paintlab
