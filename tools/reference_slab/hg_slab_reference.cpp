// Independent reference BRDF of an index-matched Henyey-Greenstein slab over a
// black surface: single scattering in closed form (Chandrasekhar 1960, sec. 47)
// plus every higher order by a Monte Carlo point estimator (next-event
// estimation towards each viewing direction). It shares no code with the
// engine: no delta-M, no Legendre or Fourier truncation, no quadrature.
//
//   build: g++ -O2 -std=c++20 -pthread hg_slab_reference.cpp -o hg_slab_reference
//   run:   ./hg_slab_reference PHOTONS_PER_INCIDENCE [SEED] > reference.csv
//
// Output (CSV): albedo, optical thickness, g, theta_i, theta_o, phi_o (degrees;
// phi_o = 0 is the light's side, 180 the mirror side), the BRDF (1/sr), its
// standard error, and the single-scattering part (exact).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <thread>
#include <vector>

namespace {

constexpr double kPi = std::numbers::pi;

struct Slab {
    double a, tau, g;
};
struct View {
    double theta_deg, phi_deg;
};
struct Vec {
    double x, y, z;
};

// xoshiro256** (Blackman & Vigna), seeded by splitmix64.
class Rng {
public:
    explicit Rng(std::uint64_t seed) {
        for (auto& s : m_s) {
            seed += 0x9e3779b97f4a7c15ULL;
            std::uint64_t z = seed;
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            s = z ^ (z >> 31);
        }
    }
    double uniform() {  // (0, 1)
        const std::uint64_t r = rotl(m_s[1] * 5, 7) * 9;
        const std::uint64_t t = m_s[1] << 17;
        m_s[2] ^= m_s[0];
        m_s[3] ^= m_s[1];
        m_s[1] ^= m_s[2];
        m_s[0] ^= m_s[3];
        m_s[2] ^= t;
        m_s[3] = rotl(m_s[3], 45);
        return (static_cast<double>(r >> 11) + 0.5) * 0x1.0p-53;
    }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::array<std::uint64_t, 4> m_s{};
};

double hg(double g, double cos_theta) {  // normalised to a 4 pi average of 1
    const double d = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (d * std::sqrt(d));
}

// A direction with cosine cos_theta to d, by inversion of the HG distribution.
Vec scatter(const Vec& d, double g, Rng& rng) {
    double c;
    const double u = rng.uniform();
    if (std::abs(g) < 1e-6) {
        c = 2.0 * u - 1.0;
    } else {
        const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        c = (1.0 + g * g - s * s) / (2.0 * g);
    }
    c = std::clamp(c, -1.0, 1.0);
    const double sn = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = 2.0 * kPi * rng.uniform();
    // An orthonormal frame around d.
    Vec t = std::abs(d.z) < 0.9 ? Vec{-d.y, d.x, 0.0} : Vec{0.0, -d.z, d.y};
    const double tl = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    t = {t.x / tl, t.y / tl, t.z / tl};
    const Vec b{d.y * t.z - d.z * t.y, d.z * t.x - d.x * t.z, d.x * t.y - d.y * t.x};
    const double cp = sn * std::cos(phi), sp = sn * std::sin(phi);
    return {c * d.x + cp * t.x + sp * b.x, c * d.y + cp * t.y + sp * b.y, c * d.z + cp * t.z + sp * b.z};
}

Vec viewDirection(const View& v) {
    const double t = v.theta_deg * kPi / 180.0, p = v.phi_deg * kPi / 180.0;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// Orders >= 2 for a beam arriving at theta_i, per view: mean and standard error.
void higherOrders(const Slab& slab, double theta_i_deg, const std::vector<View>& views, long photons,
                  std::uint64_t seed, std::vector<double>& mean, std::vector<double>& error) {
    const double ti = theta_i_deg * kPi / 180.0;
    const Vec d0{-std::sin(ti), 0.0, -std::cos(ti)};  // propagation, z up, top at z = 0, depth = -z
    std::vector<Vec> wo;
    for (const View& v : views) wo.push_back(viewDirection(v));
    const int threads = 2;
    std::vector<std::vector<double>> sum(threads, std::vector<double>(views.size(), 0.0));
    std::vector<std::vector<double>> sum2 = sum;
    std::vector<std::thread> pool;
    for (int th = 0; th < threads; ++th) {
        pool.emplace_back([&, th] {
            Rng rng(seed * 1000003ULL + static_cast<std::uint64_t>(th) * 7919ULL + 1ULL);
            std::vector<double> score(views.size());
            const double mu_i = -d0.z;
            const double w_first = -std::expm1(-slab.tau / mu_i);  // forced first collision
            for (long p = th; p < photons; p += threads) {
                std::fill(score.begin(), score.end(), 0.0);
                // First collision depth, exponential truncated to the slab.
                double depth = -mu_i * std::log1p(-rng.uniform() * w_first);
                double w = w_first * slab.a;
                Vec d = scatter(d0, slab.g, rng);
                while (true) {
                    const double s = -std::log(rng.uniform());
                    depth -= s * d.z;
                    if (depth <= 0.0 || depth >= slab.tau) break;
                    for (std::size_t k = 0; k < wo.size(); ++k) {
                        const double cos_theta = d.x * wo[k].x + d.y * wo[k].y + d.z * wo[k].z;
                        score[k] += w * slab.a * hg(slab.g, cos_theta) / (4.0 * kPi) *
                                    std::exp(-depth / wo[k].z) / wo[k].z;
                    }
                    w *= slab.a;
                    if (w < 1e-4) {  // Russian roulette
                        if (rng.uniform() > 0.1) break;
                        w *= 10.0;
                    }
                    d = scatter(d, slab.g, rng);
                }
                for (std::size_t k = 0; k < wo.size(); ++k) {
                    sum[th][k] += score[k];
                    sum2[th][k] += score[k] * score[k];
                }
            }
        });
    }
    for (auto& t : pool) t.join();
    mean.assign(views.size(), 0.0);
    error.assign(views.size(), 0.0);
    for (std::size_t k = 0; k < views.size(); ++k) {
        double s = 0.0, s2 = 0.0;
        for (int th = 0; th < threads; ++th) {
            s += sum[th][k];
            s2 += sum2[th][k];
        }
        const double n = static_cast<double>(photons);
        mean[k] = s / n;
        error[k] = std::sqrt(std::max(0.0, s2 / n - mean[k] * mean[k]) / (n - 1.0));
    }
}

double singleScattering(const Slab& slab, double theta_i_deg, const View& v) {
    const double ti = theta_i_deg * kPi / 180.0;
    const Vec d0{-std::sin(ti), 0.0, -std::cos(ti)};
    const Vec o = viewDirection(v);
    const double mu_i = -d0.z, mu_o = o.z;
    const double cos_theta = d0.x * o.x + d0.y * o.y + d0.z * o.z;
    return slab.a * hg(slab.g, cos_theta) / (4.0 * kPi) * -std::expm1(-slab.tau * (1.0 / mu_i + 1.0 / mu_o)) /
           (mu_i + mu_o);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s PHOTONS_PER_INCIDENCE [SEED]\n", argv[0]);
        return 2;
    }
    const long photons = std::atol(argv[1]);
    const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
    const std::vector<Slab> slabs{{0.9, 1.0, 0.9},  {1.0, 1.0, 0.9},  {0.9, 1.0, 0.95},  {0.99, 4.0, 0.95},
                                  {0.5, 0.5, 0.95}, {0.95, 2.0, 0.8}, {0.99, 4.0, 0.75}, {0.9, 1.0, 0.5},
                                  {0.8, 2.0, 0.0},  {0.9, 8.0, 0.9}};
    const std::vector<double> incidences{0.0, 30.0, 60.0, 80.0};
    std::vector<View> views{{0.0, 0.0}};
    for (double t : {20.0, 40.0, 60.0, 75.0, 85.0})
        for (double p : {0.0, 90.0, 180.0}) views.push_back({t, p});
    std::printf(
        "albedo,optical_thickness,g,theta_i_deg,theta_o_deg,phi_o_deg,brdf_per_sr,standard_error_per_sr,"
        "single_scattering_per_sr\n");
    std::uint64_t run = seed;
    for (const Slab& slab : slabs) {
        for (double ti : incidences) {
            std::vector<double> mean, error;
            higherOrders(slab, ti, views, photons, run++, mean, error);
            for (std::size_t k = 0; k < views.size(); ++k) {
                const double ss = singleScattering(slab, ti, views[k]);
                std::printf("%g,%g,%g,%g,%g,%g,%.7e,%.3e,%.7e\n", slab.a, slab.tau, slab.g, ti,
                            views[k].theta_deg, views[k].phi_deg, ss + mean[k], error[k], ss);
            }
            std::fflush(stdout);
        }
    }
    return 0;
}
