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
// current value, clipped to what the declaration allows.
struct SliderRange {
    double lo = 0.0;
    double hi = 1.0;
};
SliderRange sliderRange(const ParameterDecl& decl, double value);

}  // namespace paintlab::gui
