#pragma once
// The addressable numeric fields of a recipe, by the stable paths of
// recipe_paths.h (the recipe file's JSON keys, dotted, arrays from 0): what a
// fit may free, what `paintlab-cli fit --help` lists and what the Match dock
// ticks. Built on the recipe's one traversal hook (recipe.h), so a new
// declared field becomes addressable without a change here.
//
// Addressable:
//   ambient.refractive_index
//   layers[i].thickness_um
//   layers[i].binder.<key>                       (constant spectra only)
//   layers[i].components[j].<scalar key>         e.g. volume_fraction, hg_g
//   layers[i].components[j].<key>                constant spectra (e.g. a raw medium's albedo)
//   layers[i].components[j].depth_profile.weight[k]
//   substrate.<key>                              scalars and constant spectra (e.g. substrate.albedo)
// Not addressable (InputError "not a number"): tabulated spectra, depth
// profile depths (their order is a constraint, not a bound), names, kinds.

#include "paintlab/engine/parameters.h"
#include "paintlab/engine/recipe.h"

#include <string>
#include <string_view>
#include <vector>

namespace paintlab::fit {

struct ParameterPath {
    std::string path;                     // "layers[1].components[0].volume_fraction"
    std::string label;                    // for people: "basecoat > hematite > Volume fraction"
    const ParameterDecl* decl = nullptr;  // its declaration (key, unit, ranges)
    double value = 0.0;                   // in the recipe
    // The allowed range of the declaration (parameters.h), the technological
    // limits: the default bounds of a fit. Where the minimum is exclusive (a
    // thickness > 0) min is the typical minimum instead, a value the recipe
    // may take.
    double min = 0.0;
    double max = 0.0;
    // Concentrations and thicknesses whose allowed range spans decades: the
    // fitter searches them on a log scale when the lower bound is > 0.
    bool log_scale_suited = false;
};

// Every addressable field of the recipe, in recipe order (layers top first,
// each layer's own fields, then its components', then the substrate).
std::vector<ParameterPath> listParameterPaths(const Recipe& recipe);

// The field at `path`. Throws InputError(source "<argument>", field path) if
// the path does not exist in this recipe ("layers[3]: the recipe has 2
// layers") or names something that is not one number (a tabulated spectrum,
// a depth-profile depth, a name).
ParameterPath describeParameter(const Recipe& recipe, std::string_view path);
double parameterValue(const Recipe& recipe, std::string_view path);
// Sets the field (a constant spectrum becomes the new constant). Throws as
// describeParameter; does not check the value against the range (the recipe
// validation does).
void setParameterValue(Recipe& recipe, std::string_view path, double value);

}  // namespace paintlab::fit
