#pragma once
// The editable scalar parameters of a recipe, found through the recipe
// structs' traversal hooks (recipe.h), so that the editor shows exactly the
// fields that validation, JSON I/O and the fitter know, with their declared
// units and ranges (parameters.h). Qt-free: the tests use it directly.

#include "paintlab/engine/parameters.h"
#include "paintlab/engine/recipe.h"

#include <string>
#include <vector>

namespace paintlab::gui {

// Where a scalar lives: the layer, and the component in it (or none: the
// layer's own field, such as its thickness).
struct ParameterRef {
    int layer = 0;
    int component = -1;  // -1: the layer itself
    const ParameterDecl* decl = nullptr;
    // "basecoat > blue interference pearl > Volume fraction"
    std::string label;

    friend bool operator==(const ParameterRef& a, const ParameterRef& b) {
        return a.layer == b.layer && a.component == b.component && a.decl == b.decl;
    }
};

// Every scalar field of every layer and component, top layer first.
std::vector<ParameterRef> editableParameters(const Recipe& recipe);

// The field itself; nullptr if the recipe has no such layer, component or field.
double* scalarField(Recipe& recipe, const ParameterRef& ref);
const double* scalarField(const Recipe& recipe, const ParameterRef& ref);

// The slider range of a parameter: its typical range widened to hold the
// current value, clipped to what the declaration allows. Thicknesses and
// volume fractions move on a logarithmic scale (a drag changes them by a
// factor, as labs vary them: 20 -> 40 µm as far as 2 -> 4 µm), over three
// decades at most below the top when the range starts at 0; the rest linearly.
struct SliderRange {
    double lo = 0.0;
    double hi = 1.0;
    bool log = false;
    // Position in [0, 1] of a value (clamped), and the value at a position.
    double position(double value) const;
    double valueAt(double position) const;
};
SliderRange sliderRange(const ParameterDecl& decl, double value);

// Whether a parameter is a thickness or a concentration (logarithmic slider).
bool isLogarithmic(const ParameterDecl& decl);

// The unit people read a parameter in, and the factor from the recipe's
// value to it: volume fractions in % (as the component table shows them),
// the rest in their declared unit ("" for dimensionless).
struct DisplayUnit {
    std::string unit;
    double scale = 1.0;
};
DisplayUnit displayUnit(const ParameterDecl& decl);

// What a value typed into a parameter's field does. `text` is read as a
// number in the display unit (scientific notation allowed: "1e3"); the
// value (in the recipe's unit) is applied unless refused.
struct TypedValue {
    enum class Verdict { Apply, ApplyWithWarning, Refuse, NotANumber };
    Verdict verdict = Verdict::NotANumber;
    double value = 0.0;   // in the recipe's unit
    std::string message;  // why it was refused or what is unusual; empty if nothing
};
TypedValue checkTypedValue(const ParameterDecl& decl, const std::string& text);

// "40 µm", "6 %": a value in its display unit, 6 significant digits.
std::string displayText(const ParameterDecl& decl, double value);

}  // namespace paintlab::gui
