#include "paintlab/engine/fit/parameter_paths.h"

#include "paintlab/engine/error.h"

namespace paintlab::fit {

std::vector<ParameterPath> listParameterPaths(const Recipe& /*recipe*/) { throw Error("not implemented"); }
ParameterPath describeParameter(const Recipe& /*recipe*/, std::string_view /*path*/) {
    throw Error("not implemented");
}
double parameterValue(const Recipe& /*recipe*/, std::string_view /*path*/) { throw Error("not implemented"); }
void setParameterValue(Recipe& /*recipe*/, std::string_view /*path*/, double /*value*/) {
    throw Error("not implemented");
}

}  // namespace paintlab::fit
