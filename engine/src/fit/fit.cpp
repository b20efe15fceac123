#include "paintlab/engine/fit/fit.h"

namespace paintlab::fit {

std::string_view sideName(Side side) { return side == Side::Top ? "top" : "bottom"; }
void validateFitProblem(const FitProblem& /*problem*/) { throw Error("not implemented"); }
FitResult fitRecipe(const FitProblem& /*problem*/, const FitProgressCallback& /*progress*/) {
    throw Error("not implemented");
}
Recipe recipeSeenFromBelow(const Recipe& /*recipe*/) { throw Error("not implemented"); }

}  // namespace paintlab::fit
