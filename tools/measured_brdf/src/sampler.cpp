#include "paintlab/measured_brdf/sampler.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/multiangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace paintlab::measured {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Uniform in [0, 1) from the generator's top 53 bits: the same on every
// platform (std::uniform_real_distribution is not specified bit for bit).
class Uniform {
public:
    explicit Uniform(std::uint64_t seed) : m_engine(seed) {}
    double operator()() { return static_cast<double>(m_engine() >> 11) * 0x1.0p-53; }

private:
    std::mt19937_64 m_engine;
};

double round2(double deg) { return std::round(deg * 100.0) / 100.0; }

// Angles of a unit vector, rounded to 0.01°, phi in [0, 360).
SampleDirection withView(double theta_i_deg, double phi_i_deg, const Direction& wo) {
    double phi = std::atan2(wo.y, wo.x) / kDeg;
    if (phi < 0.0) phi += 360.0;
    const double theta = std::acos(std::clamp(wo.z, -1.0, 1.0)) / kDeg;
    return {round2(theta_i_deg), round2(phi_i_deg), round2(theta), round2(phi >= 359.995 ? 0.0 : phi)};
}

// A direction at angle delta (rad) from `axis` in azimuth psi (rad) around it.
Direction around(const Direction& axis, double delta, double psi) {
    // An orthonormal frame (t, b, axis).
    const Direction helper = std::abs(axis.z) < 0.9 ? Direction{0.0, 0.0, 1.0} : Direction{1.0, 0.0, 0.0};
    Direction t{helper.y * axis.z - helper.z * axis.y, helper.z * axis.x - helper.x * axis.z,
                helper.x * axis.y - helper.y * axis.x};
    const double n = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    t = {t.x / n, t.y / n, t.z / n};
    const Direction b{axis.y * t.z - axis.z * t.y, axis.z * t.x - axis.x * t.z, axis.x * t.y - axis.y * t.x};
    const double s = std::sin(delta) * std::cos(psi);
    const double u = std::sin(delta) * std::sin(psi);
    const double c = std::cos(delta);
    return {s * t.x + u * b.x + c * axis.x, s * t.y + u * b.y + c * axis.y, s * t.z + u * b.z + c * axis.z};
}

bool viewable(const Direction& wo) { return wo.z >= std::cos(kMaxThetaDeg * kDeg) - 1e-12; }

}  // namespace

Direction SampleDirection::wi() const { return directionFromAnglesDeg(theta_i_deg, phi_i_deg); }
Direction SampleDirection::wo() const { return directionFromAnglesDeg(theta_o_deg, phi_o_deg); }

std::vector<SampleDirection> sampleDirections(std::size_t count, std::uint64_t seed) {
    if (count < 100)
        throw InputError("<argument>", "count", "at least 100 samples, got " + std::to_string(count));
    std::vector<SampleDirection> out;
    out.reserve(count);

    // The six multi-angle geometries, each with 4 neighbours 2° away.
    for (double aspecular : kAspecularAnglesDeg) {
        const MultiAngleGeometry g = multiAngleGeometry(aspecular);
        out.push_back(withView(kMultiAngleIlluminationDeg, 0.0, g.wo));
        for (int k = 0; k < 4; ++k)
            out.push_back(withView(kMultiAngleIlluminationDeg, 0.0,
                                   around(g.wo, 2.0 * kDeg, k * 0.5 * std::numbers::pi)));
    }

    // The rest in three groups of about equal size, each stratified in
    // incidence: sample j of n has θi in [80° j/n, 80° (j+1)/n).
    Uniform uniform(seed);
    const std::size_t rest = count - out.size();
    const std::size_t in_plane = rest / 3;
    const std::size_t specular = rest / 3;
    const std::size_t hemisphere = rest - in_plane - specular;
    const auto incidence = [&](std::size_t j, std::size_t n) {
        return kMaxThetaDeg * (static_cast<double>(j) + uniform()) / static_cast<double>(n);
    };
    for (std::size_t j = 0; j < in_plane; ++j) {
        const double theta_i = incidence(j, in_plane);
        // Signed in-plane view angle, negative on the specular side; uniform
        // over [-80°, 80°].
        const double signed_view = kMaxThetaDeg * (2.0 * uniform() - 1.0);
        out.push_back(withView(
            theta_i, 0.0, directionFromAnglesDeg(std::abs(signed_view), signed_view < 0.0 ? 180.0 : 0.0)));
    }
    for (std::size_t j = 0; j < specular; ++j) {
        const double theta_i = incidence(j, specular);
        const Direction mirror = directionFromAnglesDeg(theta_i, 180.0);
        Direction wo;
        do {
            const double u = uniform();
            wo = around(mirror, 20.0 * kDeg * u * u, 2.0 * std::numbers::pi * uniform());
        } while (!viewable(wo));
        out.push_back(withView(theta_i, 0.0, wo));
    }
    for (std::size_t j = 0; j < hemisphere; ++j) {
        const double theta_i = incidence(j, hemisphere);
        Direction wo;
        do {  // cosine-distributed: sin θo = sqrt(u)
            const double sin_theta = std::sqrt(uniform());
            const double phi = 2.0 * std::numbers::pi * uniform();
            wo = {sin_theta * std::cos(phi), sin_theta * std::sin(phi),
                  std::sqrt(1.0 - sin_theta * sin_theta)};
        } while (!viewable(wo));
        out.push_back(withView(theta_i, 0.0, wo));
    }
    return out;
}

std::string samplesCsv(const RgbBrdf& brdf, const std::vector<SampleDirection>& directions) {
    std::string text = "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,R,G,B\n";
    for (const SampleDirection& d : directions) {
        const RgbValue f = brdf.eval(d.wi(), d.wo());
        text += io::csvJoin({io::csvNumber(d.theta_i_deg), io::csvNumber(d.phi_i_deg),
                             io::csvNumber(d.theta_o_deg), io::csvNumber(d.phi_o_deg), io::csvNumber(f[0]),
                             io::csvNumber(f[1]), io::csvNumber(f[2])});
    }
    return text;
}

double cosineLogRms(const RgbBrdf& model, const RgbBrdf& reference,
                    const std::vector<SampleDirection>& directions) {
    double sum = 0.0;
    for (const SampleDirection& d : directions) {
        const Direction wi = d.wi();
        const Direction wo = d.wo();
        const RgbValue f = model.eval(wi, wo);
        const RgbValue ref = reference.eval(wi, wo);
        for (std::size_t c = 0; c < 3; ++c) {
            const double r = cosineLogResidual(f[c], ref[c], wi.z);
            sum += r * r;
        }
    }
    return directions.empty() ? 0.0 : std::sqrt(sum / (3.0 * static_cast<double>(directions.size())));
}

}  // namespace paintlab::measured
