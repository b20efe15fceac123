#include "paintlab/engine/fit/simulate.h"

#include "paintlab/engine/error.h"

namespace paintlab::fit {

MultiAngleMeasurement standardMultiAngleMeasurement(Side /*side*/, std::vector<double> /*wavelengths_nm*/) {
    throw Error("not implemented");
}
Observations simulateObservations(const Recipe& /*recipe*/, const Observations& /*at*/, Preset /*preset*/) {
    throw Error("not implemented");
}
void addMeasurementNoise(Observations& /*observations*/, std::uint64_t /*seed*/) {
    throw Error("not implemented");
}

}  // namespace paintlab::fit
