#include "paintlab/measured_brdf/analytic_brdf.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"

#include "json_reader.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace paintlab::measured {
namespace {

struct HalfAngles {
    double cos_theta_h = 1.0;
    double cos_theta_d = 1.0;  // wi . h = wo . h
};

HalfAngles halfAngles(const Direction& wi, const Direction& wo) {
    const double hx = wi.x + wo.x;
    const double hy = wi.y + wo.y;
    const double hz = wi.z + wo.z;
    const double norm = std::sqrt(hx * hx + hy * hy + hz * hz);
    return {hz / norm, std::clamp((wi.x * hx + wi.y * hy + wi.z * hz) / norm, 0.0, 1.0)};
}

// The table without its comment lines.
io::CsvTable readTable(const std::filesystem::path& file) {
    constexpr std::size_t kMaxBytes = 1u << 20;  // a hundred materials are ~40 kB
    std::istringstream in(jsonio::readBoundedTextFile(file, kMaxBytes));
    std::string text;
    for (std::string line; std::getline(in, line);)
        text += line.starts_with('#') ? std::string() : line + "\n";  // keeps line numbers
    return io::CsvTable::parse(text, file.string());
}

RgbValue channels(const io::CsvTable& table, const io::CsvRecord& record, const std::string& column) {
    return {table.requiredNumber(record, column + "_r"), table.requiredNumber(record, column + "_g"),
            table.requiredNumber(record, column + "_b")};
}

// One parameter set per record (name column plus what fill reads).
template <class Parameters, class Fill>
std::vector<Parameters> loadRows(const std::filesystem::path& file,
                                 std::initializer_list<std::string_view> columns, const Fill& fill) {
    const io::CsvTable table = readTable(file);
    table.requireColumns(columns);
    std::vector<Parameters> out;
    for (const io::CsvRecord& record : table.records()) {
        Parameters p;
        p.name = table.field(record, "name");
        fill(table, record, p);
        out.push_back(std::move(p));
    }
    if (out.empty()) throw InputError(file.string(), "", "no material");
    return out;
}

}  // namespace

double dielectricFresnel(double cos_theta, double eta) {
    const double c = std::clamp(cos_theta, 0.0, 1.0);
    const double g2 = eta * eta - 1.0 + c * c;
    if (g2 <= 0.0) return 1.0;
    const double g = std::sqrt(g2);
    const double a = (g - c) / (g + c);
    const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

RgbValue AbcBrdf::eval(const Direction& wi, const Direction& wo) const {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {0.0, 0.0, 0.0};
    const HalfAngles h = halfAngles(wi, wo);
    const double shadowing = std::min(
        {1.0, 2.0 * h.cos_theta_h * wi.z / h.cos_theta_d, 2.0 * h.cos_theta_h * wo.z / h.cos_theta_d});
    const double fresnel = dielectricFresnel(h.cos_theta_d, m_p.ior);
    const double lobe = std::pow(1.0 + m_p.B * (1.0 - h.cos_theta_h), -m_p.C);
    RgbValue f{};
    for (std::size_t c = 0; c < 3; ++c)
        f[c] = std::max(0.0, m_p.kD[c] / std::numbers::pi +
                                 fresnel * m_p.A[c] * lobe * shadowing / (std::numbers::pi * wi.z * wo.z));
    return f;
}

RgbValue SgdBrdf::eval(const Direction& wi, const Direction& wo) const {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {0.0, 0.0, 0.0};
    const HalfAngles h = halfAngles(wi, wo);
    const double c2 = h.cos_theta_h * h.cos_theta_h;
    const double tan2 = (1.0 - c2) / c2;
    const double theta_i = std::acos(std::clamp(wi.z, -1.0, 1.0));
    const double theta_o = std::acos(std::clamp(wo.z, -1.0, 1.0));
    const double schlick5 = std::pow(1.0 - h.cos_theta_d, 5.0);
    RgbValue f{};
    for (std::size_t c = 0; c < 3; ++c) {
        const double a = m_p.alpha[c] + tan2 / m_p.alpha[c];
        const double ndf = m_p.kap[c] * std::exp(-a) / (std::numbers::pi * std::pow(a, m_p.p[c]) * c2 * c2);
        const double fresnel = m_p.f0[c] - h.cos_theta_d * m_p.f1[c] + schlick5 * (1.0 - m_p.f0[c]);
        const auto g1 = [&](double theta) {
            const double over = std::max(0.0, theta - m_p.theta0[c]);
            return std::clamp(1.0 + m_p.lambda[c] * (1.0 - std::exp(m_p.c[c] * std::pow(over, m_p.k[c]))),
                              0.0, 1.0);
        };
        const double specular = m_p.rho_s[c] * fresnel * ndf * g1(theta_i) * g1(theta_o) / (wi.z * wo.z);
        f[c] = std::max(0.0, (m_p.rho_d[c] + specular) / std::numbers::pi);
    }
    return f;
}

std::vector<AbcParameters> loadAbcParameters(const std::filesystem::path& file) {
    return loadRows<AbcParameters>(
        file, {"name", "kD_r", "A_r", "B", "C", "ior"},
        [](const io::CsvTable& table, const io::CsvRecord& record, AbcParameters& p) {
            p.kD = channels(table, record, "kD");
            p.A = channels(table, record, "A");
            p.B = table.requiredNumber(record, "B");
            p.C = table.requiredNumber(record, "C");
            p.ior = table.requiredNumber(record, "ior");
        });
}

std::vector<SgdParameters> loadSgdParameters(const std::filesystem::path& file) {
    return loadRows<SgdParameters>(
        file,
        {"name", "rhoD_r", "rhoS_r", "alpha_r", "p_r", "f0_r", "f1_r", "kap_r", "lambda_r", "c_r", "k_r",
         "theta0_r"},
        [](const io::CsvTable& table, const io::CsvRecord& record, SgdParameters& p) {
            p.rho_d = channels(table, record, "rhoD");
            p.rho_s = channels(table, record, "rhoS");
            p.alpha = channels(table, record, "alpha");
            p.p = channels(table, record, "p");
            p.f0 = channels(table, record, "f0");
            p.f1 = channels(table, record, "f1");
            p.kap = channels(table, record, "kap");
            p.lambda = channels(table, record, "lambda");
            p.c = channels(table, record, "c");
            p.k = channels(table, record, "k");
            p.theta0 = channels(table, record, "theta0");
        });
}

}  // namespace paintlab::measured
