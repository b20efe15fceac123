// Decoding a ray map's paint records into the relight kernel's arrays
// (relight_input.h): everything that depends on the geometry only.

#include "record_layout.h"
#include "relight_grid.h"
#include "sampling.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/relight_input.h"

#include <Imath/half.h>
#include <tbb/parallel_for.h>

#include <chrono>

namespace paintlab::raymaps {

PaintSample decodePaintSample(const RayMap& map, const RayMapBand& band, std::size_t index) {
    const RayMapHeader& h = map.header();
    const RecordLayout layout{h.cells, h.orders, static_cast<int>(h.lights.size())};
    if (index >= band.record_count)
        throw Error(map.path().string() + ": paint record " + std::to_string(index + 1) + " of a band of " +
                    std::to_string(band.record_count));
    const std::byte* rec = band.records.data() + index * layout.bytes();
    PaintSample s;
    s.pixel = recordField<std::uint32_t>(rec + RecordLayout::kPixel);
    s.normal = recordDirection(rec + RecordLayout::kNormal).cast<float>();
    s.view = recordDirection(rec + RecordLayout::kView).cast<float>();
    for (std::size_t c = 0; c < 3; ++c) {
        const auto e = static_cast<Eigen::Index>(c);
        s.position[e] = recordField<float>(rec + RecordLayout::kPosition + 4 * c);
        s.weight[e] = recordHalf(rec + RecordLayout::kWeight + 2 * c);
    }
    s.footprint = recordHalf(rec + RecordLayout::kFootprint);
    for (std::size_t k = 0; k < h.lights.size(); ++k)
        s.visibility.push_back(static_cast<float>(recordField<std::uint8_t>(rec + layout.visibility() + k)) /
                               255.0F);
    return s;
}

RelightInput::RelightInput(const RayMap& map) {
    const auto start = std::chrono::steady_clock::now();
    map.loadAll();
    const RayMapHeader& h = map.header();
    m_width = h.width;
    m_height = h.height;
    m_cells = h.cells;
    m_orders = h.orders;
    m_lights = static_cast<int>(h.lights.size());
    m_light_list = h.lights;
    const RecordLayout layout{h.cells, h.orders, m_lights};
    const std::size_t stride = layout.bytes();
    const auto cells = static_cast<std::size_t>(h.cells);
    const auto orders = static_cast<std::size_t>(h.orders);
    const auto lights = static_cast<std::size_t>(m_lights);

    std::vector<std::size_t> band_start(static_cast<std::size_t>(map.bandCount()) + 1, 0);
    for (int b = 0; b < map.bandCount(); ++b)
        band_start[static_cast<std::size_t>(b) + 1] =
            band_start[static_cast<std::size_t>(b)] + map.band(b).record_count;
    const std::size_t n = band_start.back();
    m_baked.assign(static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height) * 3, 0.0F);
    m_pixel.assign(n, 0);
    m_fine.assign(n, 0);
    m_to.assign(n, 0.0F);
    m_l0.assign(n * 3 * cells, 0.0F);
    // At least one element: the kernel forms pointers into it even for M_L = 1.
    m_q.assign(std::max<std::size_t>(1, n * 3 * (orders - 1) * cells), 0);
    m_mirror.assign(n * 3, 0.0F);
    m_light_at.assign(n * lights, 0);
    m_light_t.assign(n * lights * 2, 0.0F);
    m_light_s.assign(n * lights * 3, 0.0F);

    tbb::parallel_for(0, map.bandCount(), [&](int b) {
        const RayMapBand& band = map.band(b);
        float* baked =
            m_baked.data() + static_cast<std::size_t>(band.first_row) * static_cast<std::size_t>(m_width) * 3;
        for (std::size_t v = 0; v < band.baked.size(); ++v) {
            Imath::half half;
            half.setBits(band.baked[v]);
            baked[v] = static_cast<float>(half);
        }
        for (std::size_t r = 0; r < band.record_count; ++r) {
            const std::size_t i = band_start[static_cast<std::size_t>(b)] + r;
            const std::byte* rec = band.records.data() + r * stride;
            m_pixel[i] = recordField<std::uint32_t>(rec + RecordLayout::kPixel);
            const Eigen::Vector3d nrm = recordDirection(rec + RecordLayout::kNormal);
            const Eigen::Vector3d view = recordDirection(rec + RecordLayout::kView);
            const Eigen::Vector3d position =
                Eigen::Vector3f(recordField<float>(rec + RecordLayout::kPosition),
                                recordField<float>(rec + RecordLayout::kPosition + 4),
                                recordField<float>(rec + RecordLayout::kPosition + 8))
                    .cast<double>();
            Eigen::Vector3f w;
            for (std::size_t c = 0; c < 3; ++c)
                w[static_cast<Eigen::Index>(c)] = recordHalf(rec + RecordLayout::kWeight + 2 * c);
            const double mu_o = std::clamp(nrm.dot(view), 0.0, 1.0);
            int ko = 0;
            float to = 0.0F;
            grid::muIndex(mu_o, ko, to);
            m_fine[i] = static_cast<std::uint32_t>(grid::fineIndex(ko, to));
            m_to[i] = to;
            // Seen along the normal the BRDF does not depend on the azimuth: any tangent does.
            Eigen::Vector3d tangent = view - mu_o * nrm;
            const double t_len = tangent.norm();
            tangent = t_len > 1e-9 ? Eigen::Vector3d(tangent / t_len) : Eigen::Vector3d::Zero();
            const auto* q = reinterpret_cast<const std::int8_t*>(rec + layout.momentsM());
            for (std::size_t c = 0; c < 3; ++c) {
                const float wc = w[static_cast<Eigen::Index>(c)];
                for (std::size_t j = 0; j < cells; ++j) {
                    m_l0[(i * 3 + c) * cells + j] =
                        wc * recordHalf(rec + RecordLayout::kMoments0 + 6 * j + 2 * c);
                    for (std::size_t m = 1; m < orders; ++m)
                        m_q[((i * 3 + c) * (orders - 1) + m - 1) * cells + j] =
                            q[3 * ((orders - 1) * j + (m - 1)) + c];
                }
                m_mirror[i * 3 + c] = wc * recordField<float>(rec + RecordLayout::kMirror + 4 * c);
            }
            // Explicit lights: V f(wi, wo) E cos(theta_i); an unlit or
            // shadowed light gets factor 0 at a valid corner (no branch later).
            for (std::size_t k = 0; k < lights; ++k) {
                const auto vis = recordField<std::uint8_t>(rec + layout.visibility() + k);
                const ExplicitLight& light = m_light_list[k];
                Eigen::Vector3d wi = light.vector;
                Eigen::Vector3d e = light.power;
                if (light.kind == ExplicitLight::Kind::Point) {
                    wi -= position;
                    const double r2 = std::max(wi.squaredNorm(), 1e-12);
                    wi /= std::sqrt(r2);
                    e /= r2;
                }
                const double mu_i = nrm.dot(wi);
                if (vis == 0 || !(mu_i > 0.0)) continue;
                int ki = 0;
                float ti = 0.0F;
                grid::muIndex(mu_i, ki, ti);
                const Eigen::Vector3d wt = wi - mu_i * nrm;
                const double wt_len = wt.norm();
                const double cos_dphi = wt_len > 1e-9 ? wt.dot(tangent) / wt_len : 1.0;
                int kc = 0;
                float tc = 0.0F;
                grid::phiIndex(cos_dphi, kc, tc);
                m_light_at[i * lights + k] = static_cast<std::uint32_t>(grid::lightNode(ko, ki, kc));
                m_light_t[(i * lights + k) * 2] = ti;
                m_light_t[(i * lights + k) * 2 + 1] = tc;
                const double factor = vis / 255.0 * mu_i;
                for (std::size_t c = 0; c < 3; ++c)
                    m_light_s[(i * lights + k) * 3 + c] =
                        static_cast<float>(factor * e[static_cast<Eigen::Index>(c)] *
                                           static_cast<double>(w[static_cast<Eigen::Index>(c)]));
            }
        }
    });
    m_row_start.assign(static_cast<std::size_t>(m_height) + 1, n);
    std::size_t i = 0;
    for (int y = 0; y < m_height; ++y) {
        const auto row_begin = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(m_width);
        while (i < n && m_pixel[i] < row_begin) ++i;
        m_row_start[static_cast<std::size_t>(y)] = i;
    }
    m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace paintlab::raymaps
