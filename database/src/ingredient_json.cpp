// Reader of ingredient files (ingredient_json.h). Strict: every key is
// either consumed or reported as unknown, so a typo never passes silently.

#include "paintlab/database/ingredient_json.h"

#include "ingredient_json_detail.h"
#include "spectrum_checks.h"

#include "paintlab/engine/error.h"

#include "json_reader.h"

namespace paintlab::db {

namespace {

using Json = nlohmann::json;

using jsonio::ObjectReader;

// Reads spectra.<key> into the ingredient's provenance map and returns the spectrum.
class SpectraReader {
public:
    SpectraReader(ObjectReader& parent, Ingredient& ingredient, const std::string& source)
        : m_reader(parent.require("spectra", "the ingredient's spectra"), parent.fieldPath("spectra"),
                   source),
          m_ingredient(ingredient), m_source(source) {}

    bool has(std::string_view key) const { return m_reader.has(key); }

    Spectrum take(std::string_view key_view) {
        const std::string key(key_view);
        ObjectReader spectrum(m_reader.require(key, "a spectrum"), m_reader.fieldPath(key), m_source);
        SpectrumInfo info{spectrum.string("unit", true), spectrum.string("source", true),
                          spectrum.string("date", false)};
        Spectrum out;
        try {
            if (spectrum.has("value")) {
                out = Spectrum(spectrum.number("value", "a number"));
            } else {
                auto wavelengths = spectrum.numbers("wavelengths_nm", 1);
                auto values = spectrum.numbers("values", 1);
                out = Spectrum(std::move(wavelengths), std::move(values));
            }
        } catch (const std::invalid_argument& e) {
            spectrum.fail("", e.what());
        }
        spectrum.finish();
        m_ingredient.spectrum_info[key] = std::move(info);
        return out;
    }

    std::optional<Spectrum> takeOptional(std::string_view key) {
        if (!has(key)) return std::nullopt;
        return take(key);
    }

    void finish() const { m_reader.finish(); }

private:
    ObjectReader m_reader;
    Ingredient& m_ingredient;
    const std::string& m_source;
};

}  // namespace

Ingredient detail::ingredientFromJson(const nlohmann::json& json, const std::string& field,
                                      const std::string& source) {
    ObjectReader r(json, field, source);
    Ingredient ing;
    const std::string kind_text = r.string("kind", true);
    const auto kind = parseIngredientKind(kind_text);
    if (!kind)
        r.fail("kind", "unknown kind '" + kind_text +
                           "' (binder, pigment, mirror_flake, interference_flake or substrate)");
    ing.name = r.string("name", true);
    ing.description = r.string("description", false);
    ing.source = r.string("source", false);
    ing.density_g_cm3 = r.optionalNumber("density_g_cm3");
    ing.density_source = r.string("density_source", false);
    if (r.has("tags")) {
        const Json& tags = r.require("tags", "tags");
        if (!tags.is_array()) r.fail("tags", "expected an array of strings");
        for (const auto& tag : tags) {
            if (!tag.is_string()) r.fail("tags", "expected an array of strings");
            ing.tags.push_back(tag.get<std::string>());
        }
    }
    if (r.has("limits")) {
        ObjectReader limits(r.require("limits", "limits"), r.fieldPath("limits"), source);
        ing.limits = {limits.optionalNumber("max_volume_fraction"), limits.optionalNumber("min_thickness_um"),
                      limits.optionalNumber("max_thickness_um")};
        limits.finish();
    }
    SpectraReader spectra(r, ing, source);
    switch (*kind) {
    case IngredientKind::Binder: {
        Binder data;
        data.name = ing.name;
        data.refractive_index = spectra.take(params::kBinderIndex.key);
        data.absorption_per_um = spectra.take(params::kBinderAbsorption.key);
        ing.solids_mass_fraction = r.optionalNumber("solids_mass_fraction");
        ing.volatile_density_g_cm3 = r.optionalNumber("volatile_density_g_cm3");
        ing.data = std::move(data);
        break;
    }
    case IngredientKind::Pigment: {
        Pigment data;
        data.name = ing.name;
        data.source = ing.source;
        data.hg_g = r.number("hg_g", "a number");
        data.particle_diameter_um = r.number("particle_diameter_um", "a number");
        data.sigma_a_per_um = spectra.take(params::kPigmentSigmaA.key);
        data.sigma_s_per_um = spectra.take(params::kPigmentSigmaS.key);
        ing.data = std::move(data);
        break;
    }
    case IngredientKind::MirrorFlake: {
        MirrorFlake data;
        data.name = ing.name;
        data.source = ing.source;
        data.diameter_um = r.number("diameter_um", "a number");
        ing.diameter_sd_um = r.optionalNumber("diameter_sd_um").value_or(0.0);
        data.thickness_um = r.number("thickness_um", "a number");
        data.orientation_spread_deg = r.number("orientation_spread_deg", "a number");
        data.reflectance = spectra.takeOptional(params::kMirrorReflectance.key);
        data.metal_n = spectra.takeOptional(params::kMetalN.key);
        data.metal_k = spectra.takeOptional(params::kMetalK.key);
        ing.data = std::move(data);
        break;
    }
    case IngredientKind::InterferenceFlake: {
        InterferenceFlake data;
        data.name = ing.name;
        data.source = ing.source;
        data.diameter_um = r.number("diameter_um", "a number");
        ing.diameter_sd_um = r.optionalNumber("diameter_sd_um").value_or(0.0);
        data.orientation_spread_deg = r.number("orientation_spread_deg", "a number");
        data.mica_thickness_nm = r.number("mica_thickness_nm", "a number");
        data.mica_thickness_spread_nm = r.number("mica_thickness_spread_nm", "a number");
        data.tio2_thickness_nm = r.number("tio2_thickness_nm", "a number");
        data.tio2_thickness_spread_nm = r.number("tio2_thickness_spread_nm", "a number");
        data.mica_refractive_index = spectra.take(params::kMicaIndex.key);
        data.tio2_refractive_index = spectra.take(params::kTio2Index.key);
        ing.data = std::move(data);
        break;
    }
    case IngredientKind::Substrate: {
        const std::string substrate_kind = r.string("substrate_kind", true);
        if (substrate_kind == LambertianSubstrate::kKind)
            ing.data = Substrate{LambertianSubstrate{spectra.take(params::kSubstrateAlbedo.key)}};
        else if (substrate_kind == MetalSubstrate::kKind)
            ing.data = Substrate{
                MetalSubstrate{spectra.take(params::kMetalN.key), spectra.take(params::kMetalK.key)}};
        else if (substrate_kind == BlackSubstrate::kKind)
            ing.data = Substrate{BlackSubstrate{}};
        else if (substrate_kind == TransparentSubstrate::kKind)
            ing.data = Substrate{TransparentSubstrate{r.number("refractive_index", "a number")}};
        else
            r.fail("substrate_kind", "unknown substrate kind '" + substrate_kind +
                                         "' (lambertian, metal, black or transparent)");
        break;
    }
    }
    spectra.finish();
    r.finish();
    return ing;
}

namespace {

using OrderedJson = nlohmann::ordered_json;

class JsonWriter {
public:
    explicit JsonWriter(const Ingredient& ingredient) : m_ingredient(ingredient) {}

    OrderedJson write() {
        const Ingredient& ing = m_ingredient;
        m_out["kind"] = ingredientKindName(ing.kind());
        m_out["name"] = ing.name;
        m_out["description"] = ing.description;
        m_out["source"] = ing.source;
        m_out["tags"] = ing.tags;
        if (ing.density_g_cm3) m_out["density_g_cm3"] = *ing.density_g_cm3;
        m_out["density_source"] = ing.density_source;
        OrderedJson limits = OrderedJson::object();
        if (ing.limits.max_volume_fraction) limits["max_volume_fraction"] = *ing.limits.max_volume_fraction;
        if (ing.limits.min_thickness_um) limits["min_thickness_um"] = *ing.limits.min_thickness_um;
        if (ing.limits.max_thickness_um) limits["max_thickness_um"] = *ing.limits.max_thickness_um;
        m_out["limits"] = limits;
        if (ing.solids_mass_fraction) m_out["solids_mass_fraction"] = *ing.solids_mass_fraction;
        if (ing.volatile_density_g_cm3) m_out["volatile_density_g_cm3"] = *ing.volatile_density_g_cm3;
        m_spectra = OrderedJson::object();
        std::visit([this](const auto& data) { kindFields(data); }, ing.data);
        m_out["spectra"] = m_spectra;
        return std::move(m_out);
    }

    // The traversal hook's visitor: scalars become fields, spectra go under "spectra".
    void scalar(const ParameterDecl& decl, const double& value) {
        if (decl.key != "volume_fraction") m_out[std::string(decl.key)] = value;
    }
    void spectrum(const ParameterDecl& decl, const Spectrum& spectrum) {
        const std::string key(decl.key);
        const auto found = m_ingredient.spectrum_info.find(key);
        const SpectrumInfo info = found != m_ingredient.spectrum_info.end()
                                      ? found->second
                                      : SpectrumInfo{std::string(decl.unit), m_ingredient.source, {}};
        OrderedJson item;
        item["unit"] = info.unit;
        item["source"] = info.source;
        if (!info.date.empty()) item["date"] = info.date;
        item["wavelengths_nm"] = spectrum.wavelengthsNm();
        item["values"] = spectrum.values();
        m_spectra[key] = item;
    }
    void optionalSpectrum(const ParameterDecl& decl, const std::optional<Spectrum>& spectrum) {
        if (spectrum) this->spectrum(decl, *spectrum);
    }

private:
    template <class T> void kindFields(const T& data) {
        T::traverse(data, *this);
        if constexpr (std::is_same_v<T, MirrorFlake> || std::is_same_v<T, InterferenceFlake>)
            m_out["diameter_sd_um"] = m_ingredient.diameter_sd_um;
    }
    void kindFields(const Substrate& substrate) {
        m_out["substrate_kind"] = substrateKind(substrate);
        std::visit([this](const auto& s) { std::decay_t<decltype(s)>::traverse(s, *this); }, substrate);
    }

    const Ingredient& m_ingredient;
    OrderedJson m_out;
    OrderedJson m_spectra;
};

}  // namespace

nlohmann::ordered_json detail::ingredientToJson(const Ingredient& ingredient) {
    return JsonWriter(ingredient).write();
}

std::string ingredientsToJson(const std::vector<Ingredient>& ingredients) {
    OrderedJson document;
    document["format"] = "paintlab-ingredients";
    document["format_version"] = 1;
    document["ingredients"] = OrderedJson::array();
    for (const auto& ingredient : ingredients)
        document["ingredients"].push_back(detail::ingredientToJson(ingredient));
    return document.dump(2) + "\n";
}

std::vector<Ingredient> parseIngredientsJson(std::string_view text, const std::string& source) {
    const Json document = jsonio::parseUntrustedJson(text, source);
    ObjectReader r(document, "", source);
    if (r.string("format", true) != "paintlab-ingredients")
        r.fail("format", "expected \"paintlab-ingredients\"");
    const double version = r.number("format_version", "the format's version");
    if (version != 1.0) r.fail("format_version", "only version 1 is known to this build");
    r.string("generated_by", false);
    const Json& list = r.require("ingredients", "the ingredients");
    if (!list.is_array()) r.fail("ingredients", "expected an array");
    std::vector<Ingredient> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string field = r.elementPath("ingredients", i);
        out.push_back(detail::ingredientFromJson(list[i], field, source));
        detail::normaliseIngredientSpectra(out.back(), source, field);
    }
    r.finish();
    return out;
}

}  // namespace paintlab::db
