#include "paintlab/engine/parameters.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace paintlab {
namespace {

// The declarations drive validation, the GUI and the fitter: each must be
// self-consistent or every client inherits the mistake.
TEST(Parameters, EveryDeclarationIsConsistent) {
    std::set<const ParameterDecl*> seen;
    for (const ParameterDecl* decl : allParameters()) {
        SCOPED_TRACE(std::string(decl->key));
        EXPECT_TRUE(seen.insert(decl).second) << "listed twice";
        EXPECT_FALSE(decl->key.empty());
        EXPECT_FALSE(decl->label.empty());
        EXPECT_FALSE(decl->unit.empty());
        EXPECT_FALSE(decl->help.empty());
        EXPECT_LT(decl->min, decl->max);
        EXPECT_LE(decl->typicalMin, decl->typicalMax);
        // The typical range lies inside the allowed one (else a slider could reach a rejected value).
        EXPECT_GE(decl->typicalMin, decl->min);
        EXPECT_LE(decl->typicalMax, decl->max);
        if (!decl->required) {
            EXPECT_TRUE(decl->allows(decl->defaultValue)) << "default is not allowed";
        }
    }
    EXPECT_GE(seen.size(), 30u);
}

TEST(Parameters, AllowsHonoursExclusiveMinimumAndNaN) {
    EXPECT_FALSE(params::kLayerThickness.allows(0.0));
    EXPECT_TRUE(params::kLayerThickness.allows(1e-3));
    EXPECT_TRUE(params::kPigmentVolumeFraction.allows(0.0));
    EXPECT_FALSE(params::kPigmentVolumeFraction.allows(0.9));
    EXPECT_FALSE(params::kOrientationSpread.allows(std::numeric_limits<double>::quiet_NaN()));
}

}  // namespace
}  // namespace paintlab
