#pragma once
// The paint records of a ray map decoded once into the relight kernel's
// arrays (docs/RAYMAPS.md, "Relight kernel"). Everything that depends on the
// geometry alone is done here, once per map: the octahedral normals and views
// decoded, the polar angle of the view turned into table indices, every
// explicit light's direction turned into the light table's trilinear corner
// and weights (visibility, cos theta_i, irradiance and the pixel's weight
// folded into one RGB factor), the half floats widened. What is left per
// recipe change is a branch-free pass of table lookups and dot products
// (relight(const RelightInput&, ...)) whose cost depends on the number of
// paint pixels only.
//
// The geometry stays reachable for passes that run after the relight
// (sparkle, issue 7): decodePaintSample() gives the frame, view, footprint,
// position, weight and light visibilities of a record of the map; paint
// pixel i of a RelightInput is record i in band order (pixel(i) is its image
// pixel), so such a pass can walk the map's bands alongside.

#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace paintlab::raymaps {

// One paint pixel as the precompute stored it, decoded (world space).
struct PaintSample {
    std::uint32_t pixel = 0;        // row-major index in the image
    Eigen::Vector3f normal;         // shading normal, unit
    Eigen::Vector3f view;           // towards the eye, unit (after any mirror or glass)
    Eigen::Vector3f position;       // of the first paint sample in the pixel
    float footprint = 0.0F;         // pixel width at the hit, scene units
    Eigen::Vector3f weight;         // coverage x throughput, RGB
    std::vector<float> visibility;  // per explicit light of the header, 0..1
};

// Decodes record `index` of `band` (RayMap::band). Unit direction towards
// explicit light k from the sample: header().lights[k].vector for a sun,
// (vector - position).normalized() for a point light.
PaintSample decodePaintSample(const RayMap& map, const RayMapBand& band, std::size_t index);

class RelightInput {
public:
    // Loads every band of `map` (InputError naming the file and chunk if one
    // is corrupt) and decodes its records. The map may be closed afterwards.
    explicit RelightInput(const RayMap& map);

    int width() const { return m_width; }
    int height() const { return m_height; }
    int cells() const { return m_cells; }
    int orders() const { return m_orders; }
    int lights() const { return m_lights; }
    std::size_t paintPixels() const { return m_pixel.size(); }
    // Seconds spent decoding (once per map).
    double seconds() const { return m_seconds; }
    // Image pixel index of paint pixel i (ascending).
    std::uint32_t pixel(std::size_t i) const { return m_pixel[i]; }
    const std::vector<ExplicitLight>& explicitLights() const { return m_light_list; }

private:
    friend RgbImage relight(const RelightInput& input, const RelightTables& tables);
    int m_width = 0;
    int m_height = 0;
    int m_cells = 0;
    int m_orders = 0;
    int m_lights = 0;
    double m_seconds = 0.0;
    std::vector<ExplicitLight> m_light_list;
    std::vector<float> m_baked;            // width x height x 3, linear RGB
    std::vector<std::size_t> m_row_start;  // first paint pixel of each row, height + 1 entries
    std::vector<std::uint32_t> m_pixel;    // image pixel index
    // Kernel arrays, one block per paint pixel (the kernel streams them):
    std::vector<std::uint32_t> m_fine;  // nearest fine theta_o node (moment and coat tables)
    std::vector<float> m_to;            // theta_o fraction between coarse nodes (light table)
    std::vector<float> m_l0;            // [(i * 3 + c) * J + j]: weight_c x l^0_j
    std::vector<std::int8_t> m_q;       // [((i * 3 + c) * (M_L - 1) + m - 1) * J + j]: l^m_j / l^0_j x 127
    std::vector<float> m_mirror;        // [i * 3 + c]: weight_c x mirror radiance
    std::vector<std::uint32_t> m_light_at;  // [i * K + k]: light table corner (float offset)
    std::vector<float> m_light_t;           // [(i * K + k) * 2 + {0, 1}]: theta_i, dphi fractions
    std::vector<float> m_light_s;           // [(i * K + k) * 3 + c]: weight_c V E_c cos theta_i (0: unlit)
};

}  // namespace paintlab::raymaps
