#include "recipe_text.h"

#include "paintlab/engine/io/number_format.h"

#include <sstream>

namespace paintlab::cli {

namespace {

std::string number(double value) { return io::formatNumber(value, io::NumberFormat::Brief); }

std::string withUnit(double value, std::string_view unit) {
    return unit == "1" ? number(value) : number(value) + " " + std::string(unit);
}

std::string spectrumSummary(const Spectrum& s, std::string_view unit) {
    if (s.isConstant()) return withUnit(s.values().front(), unit);
    std::string text = number(s.minValue()) + " .. " + withUnit(s.maxValue(), unit) + " over " +
                       number(s.wavelengthsNm().front()) + "-" + number(s.wavelengthsNm().back()) + " nm (" +
                       std::to_string(s.values().size()) + " samples";
    if (s.wavelengthsNm().front() <= 550.0 && s.wavelengthsNm().back() >= 550.0)
        text += "; " + withUnit(s(550.0), unit) + " at 550 nm";
    return text + ")";
}

// Prints every declared field through the same traversal hook as the JSON I/O.
class FieldPrinter {
public:
    FieldPrinter(std::ostringstream& out, std::string indent) : m_out(out), m_indent(std::move(indent)) {}
    void scalar(const ParameterDecl& decl, double value) { line(decl, withUnit(value, decl.unit)); }
    void spectrum(const ParameterDecl& decl, const Spectrum& s) { line(decl, spectrumSummary(s, decl.unit)); }
    void optionalSpectrum(const ParameterDecl& decl, const std::optional<Spectrum>& s) {
        if (s) spectrum(decl, *s);
    }

private:
    void line(const ParameterDecl& decl, const std::string& value) {
        std::string label(decl.label);
        label.resize(std::max<std::size_t>(label.size(), 36), ' ');
        m_out << m_indent << label << value << '\n';
    }
    std::ostringstream& m_out;
    std::string m_indent;
};

}  // namespace

std::string describeRecipe(const Recipe& recipe) {
    std::ostringstream out;
    out << "Recipe: " << recipe.name << '\n';
    if (!recipe.description.empty()) out << "  " << recipe.description << '\n';
    out << "Ambient refractive index: " << number(recipe.ambient_refractive_index) << '\n';
    out << recipe.layers.size() << (recipe.layers.size() == 1 ? " layer" : " layers") << ", total "
        << number(recipe.totalThicknessUm()) << " µm (top first)\n";
    for (std::size_t i = 0; i < recipe.layers.size(); ++i) {
        const Layer& layer = recipe.layers[i];
        out << "\nLayer " << i + 1 << " '" << layer.name << "': " << number(layer.thickness_um) << " µm";
        if (!layer.binder.name.empty()) out << " of " << layer.binder.name;
        out << ", total volume fraction " << number(layer.totalVolumeFraction()) << '\n';
        FieldPrinter binder_printer(out, "    binder: ");
        Binder::traverse(layer.binder, binder_printer);
        for (std::size_t j = 0; j < layer.components.size(); ++j) {
            const Component& component = layer.components[j];
            out << "  Component " << j + 1 << " '" << componentName(component) << "' ("
                << componentKind(component) << ")\n";
            FieldPrinter printer(out, "    ");
            std::visit(
                [&](const auto& c) {
                    std::decay_t<decltype(c)>::traverse(c, printer);
                    if (!c.source.empty()) out << "    source: " << c.source << '\n';
                    if constexpr (requires { c.depth_profile; }) {
                        if (c.depth_profile)
                            out << "    depth profile: " << c.depth_profile->depth.size()
                                << " samples, peak/mean concentration "
                                << number(c.depth_profile->peakRelativeConcentration()) << '\n';
                    }
                },
                component);
        }
    }
    out << "\nSubstrate: " << substrateKind(recipe.substrate) << '\n';
    std::visit(
        [&out](const auto& s) {
            FieldPrinter printer(out, "    ");
            std::decay_t<decltype(s)>::traverse(s, printer);
        },
        recipe.substrate);
    return out.str();
}

}  // namespace paintlab::cli
