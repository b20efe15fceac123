#include "paintlab/measured_brdf/neural_brdf.h"

#include "paintlab/engine/error.h"

#include "json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string_view>

namespace paintlab::measured {
namespace {

// out = relu?(in W + b) for a row-major W of in.size() x out.size().
void layer(const double* in, std::size_t n_in, const std::vector<double>& w, const std::vector<double>& b,
           double* out, std::size_t n_out, bool relu) {
    for (std::size_t j = 0; j < n_out; ++j) {
        double sum = b[j];
        for (std::size_t i = 0; i < n_in; ++i) sum += in[i] * w[i * n_out + j];
        out[j] = relu ? std::max(sum, 0.0) : sum;
    }
}

// A weight matrix (rows > 1: an array of rows) or bias (rows == 1: a flat
// array), row-major.
std::vector<double> readMatrix(jsonio::ObjectReader& reader, std::string_view field, std::size_t rows,
                               std::size_t cols) {
    const nlohmann::json& value = reader.require(field, "an array");
    if (rows == 1) return reader.fixedNumberArray(field, value, cols);
    if (!value.is_array() || value.size() != rows)
        reader.fail(field,
                    "expected " + std::to_string(rows) + " rows of " + std::to_string(cols) + " numbers");
    std::vector<double> out;
    out.reserve(rows * cols);
    for (std::size_t i = 0; i < rows; ++i) {
        const std::vector<double> row =
            reader.fixedNumberArray(std::string(field) + "[" + std::to_string(i) + "]", value[i], cols);
        out.insert(out.end(), row.begin(), row.end());
    }
    return out;
}

}  // namespace

NeuralBrdf::NeuralBrdf(std::string name, std::vector<double> w1, std::vector<double> b1,
                       std::vector<double> w2, std::vector<double> b2, std::vector<double> w3,
                       std::vector<double> b3)
    : m_name(std::move(name)), m_w1(std::move(w1)), m_b1(std::move(b1)), m_w2(std::move(w2)),
      m_b2(std::move(b2)), m_w3(std::move(w3)), m_b3(std::move(b3)) {
    if (m_w1.size() != kInputs * kHidden || m_b1.size() != kHidden || m_w2.size() != kHidden * kHidden ||
        m_b2.size() != kHidden || m_w3.size() != kHidden * kOutputs || m_b3.size() != kOutputs)
        throw InputError("<argument>", m_name, "weights of the wrong size for a 6-21-21-3 network");
}

RgbValue NeuralBrdf::eval(const Direction& wi, const Direction& wo) const {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {0.0, 0.0, 0.0};
    double hx = wi.x + wo.x;
    double hy = wi.y + wo.y;
    double hz = wi.z + wo.z;
    const double norm = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= norm;
    hy /= norm;
    hz /= norm;
    const double theta_h = std::acos(std::clamp(hz, -1.0, 1.0));
    const double phi_h = std::atan2(hy, hx);
    // Rusinkiewicz's difference vector: wi rotated by -phi_h about z, then by
    // -theta_h about y (the half vector goes to the pole).
    const double cp = std::cos(-phi_h);
    const double sp = std::sin(-phi_h);
    const double x1 = cp * wi.x - sp * wi.y;
    const double y1 = sp * wi.x + cp * wi.y;
    const double ct = std::cos(-theta_h);
    const double st = std::sin(-theta_h);
    const double dx = ct * x1 + st * wi.z;
    const double dz = -st * x1 + ct * wi.z;

    const double x[kInputs] = {std::sin(theta_h), 0.0, std::cos(theta_h), dx, y1, dz};
    double h1[kHidden];
    double h2[kHidden];
    double y[kOutputs];
    layer(x, kInputs, m_w1, m_b1, h1, kHidden, true);
    layer(h1, kHidden, m_w2, m_b2, h2, kHidden, true);
    layer(h2, kHidden, m_w3, m_b3, y, kOutputs, false);
    return {std::max(std::expm1(y[0]), 0.0), std::max(std::expm1(y[1]), 0.0),
            std::max(std::expm1(y[2]), 0.0)};
}

std::vector<NeuralBrdf> loadNeuralBrdfs(const std::filesystem::path& file) {
    const std::string source = file.string();
    // The file holds a dozen 6-21-21-3 networks (about 100 kB).
    constexpr std::size_t kMaxBytes = 16u << 20;
    const nlohmann::json root =
        jsonio::parseUntrustedJson(jsonio::readBoundedTextFile(file, kMaxBytes), source);
    if (!root.is_object()) throw InputError(source, "", "expected an object of materials");
    constexpr std::size_t kIn = NeuralBrdf::kInputs;
    constexpr std::size_t kHid = NeuralBrdf::kHidden;
    constexpr std::size_t kOut = NeuralBrdf::kOutputs;
    std::vector<NeuralBrdf> out;
    for (const auto& [key, material] : root.items()) {
        if (key.starts_with("_")) continue;
        if (!material.is_object()) throw InputError(source, key, "expected an object of weights");
        jsonio::ObjectReader reader(material, key, source);
        std::vector<double> w1 = readMatrix(reader, "W1", kIn, kHid);
        std::vector<double> b1 = readMatrix(reader, "b1", 1, kHid);
        std::vector<double> w2 = readMatrix(reader, "W2", kHid, kHid);
        std::vector<double> b2 = readMatrix(reader, "b2", 1, kHid);
        std::vector<double> w3 = readMatrix(reader, "W3", kHid, kOut);
        std::vector<double> b3 = readMatrix(reader, "b3", 1, kOut);
        reader.finish();
        out.emplace_back(key, std::move(w1), std::move(b1), std::move(w2), std::move(b2), std::move(w3),
                         std::move(b3));
    }
    if (out.empty()) throw InputError(source, "", "no material");
    return out;
}

}  // namespace paintlab::measured
