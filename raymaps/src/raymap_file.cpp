// Reading ray-map files: the header (JSON) checked field by field, the bands
// read and checked on first use.

#include "raymap_io.h"
#include "record_layout.h"

#include "json_reader.h"
#include "paintlab/engine/error.h"
#include "paintlab/raymaps/raymap.h"

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

namespace paintlab::raymaps {

namespace {

using nlohmann::json;

constexpr int kMaxImageSide = 16384;

json vec3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d vector3(jsonio::ObjectReader& r, std::string_view key) {
    const std::vector<double> v = r.fixedNumberArray(key, r.require(key, "3 numbers"), 3);
    return {v[0], v[1], v[2]};
}

RayMapHeader parseHeader(const std::vector<std::byte>& payload, const std::string& file,
                         std::uint32_t version) {
    const std::string text(reinterpret_cast<const char*>(payload.data()), payload.size());
    const json j = jsonio::parseUntrustedJson(text, file);
    jsonio::ObjectReader r(j, "chunk 1 (HEAD)", file);
    RayMapHeader h;
    h.file_version = version;
    h.width = r.integerIn("width", 1, kMaxImageSide);
    h.height = r.integerIn("height", 1, kMaxImageSide);
    h.cells = r.integerIn("cells", 1, 16);
    h.orders = r.integerIn("orders", 1, 16);
    h.band_rows = r.integerIn("band_rows", 1, 4096);
    h.env_lights = r.integerIn("env_lights", 0, 255);
    h.paint_proxy_albedo = r.numberIn("paint_proxy_albedo", 0.0, 1.0);
    h.scene_file = r.string("scene_file", true);
    const json& lights = r.require("lights", "the explicit lights");
    if (!lights.is_array() || lights.size() > 255) r.fail("lights", "not an array of at most 255 lights");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        jsonio::ObjectReader l(lights[i], r.elementPath("lights", i), file);
        ExplicitLight light;
        const std::string kind = l.string("kind", true);
        if (kind == "sun")
            light.kind = ExplicitLight::Kind::Sun;
        else if (kind == "point")
            light.kind = ExplicitLight::Kind::Point;
        else
            l.fail("kind", "not 'sun' or 'point'");
        light.vector = vector3(l, "vector");
        light.power = vector3(l, "power");
        light.solid_angle_sr = l.numberIn("solid_angle_sr", 0.0, 4.0 * std::numbers::pi);
        if (light.kind == ExplicitLight::Kind::Sun && std::abs(light.vector.norm() - 1.0) > 1e-6)
            l.fail("vector", "not a unit direction");
        l.finish();
        h.lights.push_back(light);
    }
    if (version >= 2) {
        jsonio::ObjectReader camera(r.require("camera", "the camera's position and pixel angle"),
                                    r.fieldPath("camera"), file);
        h.camera_position = vector3(camera, "position");
        if (!h.camera_position.allFinite()) camera.fail("position", "not finite");
        h.pixel_angle_rad =
            camera.numberIn("pixel_angle_rad", std::numeric_limits<double>::min(), std::numbers::pi);
        camera.finish();
        h.scene_unit_m = r.numberIn("scene_unit_m", 1e-12, 1e6);
    }
    jsonio::ObjectReader stats(r.require("statistics", "precompute statistics"), r.fieldPath("statistics"),
                               file);
    h.paint_pixels = static_cast<std::uint64_t>(stats.numberIn("paint_pixels", 0.0, 1e12));
    h.rays = static_cast<std::uint64_t>(stats.numberIn("rays", 0.0, 1e18));
    h.seconds = stats.numberIn("seconds", 0.0, 1e9);
    stats.finish();
    const int record = r.integerIn("record_bytes", 1, 1 << 20);
    if (static_cast<std::size_t>(record) != recordBytes(h.cells, h.orders, static_cast<int>(h.lights.size())))
        r.fail("record_bytes", "does not match the record layout for these cells, orders and lights");
    r.finish();
    return h;
}

}  // namespace

std::string headerToJson(const RayMapHeader& h) {
    json j;
    j["width"] = h.width;
    j["height"] = h.height;
    j["cells"] = h.cells;
    j["orders"] = h.orders;
    j["band_rows"] = h.band_rows;
    j["env_lights"] = h.env_lights;
    j["paint_proxy_albedo"] = h.paint_proxy_albedo;
    j["scene_file"] = h.scene_file;
    j["record_bytes"] = recordBytes(h.cells, h.orders, static_cast<int>(h.lights.size()));
    j["camera"] = {{"position", vec3(h.camera_position)}, {"pixel_angle_rad", h.pixel_angle_rad}};
    j["scene_unit_m"] = h.scene_unit_m;
    json lights = json::array();
    for (const ExplicitLight& l : h.lights)
        lights.push_back({{"kind", l.kind == ExplicitLight::Kind::Sun ? "sun" : "point"},
                          {"vector", vec3(l.vector)},
                          {"power", vec3(l.power)},
                          {"solid_angle_sr", l.solid_angle_sr}});
    j["lights"] = lights;
    j["statistics"] = {{"paint_pixels", h.paint_pixels}, {"rays", h.rays}, {"seconds", h.seconds}};
    return j.dump(1);
}

struct RayMap::Impl {
    ChunkFileReader reader;
};

RayMap::~RayMap() = default;

const std::filesystem::path& RayMap::path() const { return m_impl->reader.path(); }

std::unique_ptr<RayMap> RayMap::open(const std::filesystem::path& path) {
    std::unique_ptr<RayMap> map(new RayMap());
    map->m_impl = std::make_unique<Impl>(Impl{ChunkFileReader(path, kRayMapMagic, kRayMapVersion)});
    const ChunkFileReader& reader = map->m_impl->reader;
    const std::string file = path.string();
    const auto& chunks = reader.chunks();
    if (chunks.empty() || chunks[0].type != kHeaderChunk)
        throw InputError(file, "chunk 1", "the first chunk is not the ray-map header (HEAD)");
    map->m_header = parseHeader(reader.read(0), file, reader.version());
    const RayMapHeader& h = map->m_header;
    map->m_record_bytes = raymaps::recordBytes(h.cells, h.orders, static_cast<int>(h.lights.size()));
    const int bands = (h.height + h.band_rows - 1) / h.band_rows;
    if (chunks.size() != 1 + 2 * static_cast<std::size_t>(bands))
        throw InputError(file, "",
                         std::to_string(chunks.size()) + " chunks; a " + std::to_string(h.height) +
                             "-row map in bands of " + std::to_string(h.band_rows) + " has " +
                             std::to_string(1 + 2 * bands));
    for (int b = 0; b < bands; ++b) {
        const auto i = 1 + 2 * static_cast<std::size_t>(b);
        if (chunks[i].type != kBakedChunk || chunks[i + 1].type != kPaintChunk)
            throw InputError(file, "chunk " + std::to_string(i + 1),
                             "expected the BAKE and PNTR chunks of band " + std::to_string(b + 1));
        map->m_bands.emplace_back();
        map->m_once.push_back(std::make_unique<std::once_flag>());
    }
    return map;
}

const RayMapBand& RayMap::band(int index) const {
    const auto b = static_cast<std::size_t>(index);
    std::call_once(*m_once.at(b), [&] {
        const ChunkFileReader& reader = m_impl->reader;
        const std::string file = reader.path().string();
        auto band = std::make_unique<RayMapBand>();
        band->first_row = index * m_header.band_rows;
        band->rows = std::min(m_header.band_rows, m_header.height - band->first_row);
        const std::size_t baked_index = 1 + 2 * b;
        const std::vector<std::byte> baked = reader.read(baked_index);
        const std::size_t values =
            3 * static_cast<std::size_t>(band->rows) * static_cast<std::size_t>(m_header.width);
        if (baked.size() != 2 * values)
            throw InputError(file, "chunk " + std::to_string(baked_index + 1) + " (BAKE)",
                             "size " + std::to_string(baked.size()) + " does not match the band's pixels");
        band->baked.resize(values);
        std::memcpy(band->baked.data(), baked.data(), baked.size());
        const std::string where = "chunk " + std::to_string(baked_index + 2) + " (PNTR)";
        band->records = reader.read(baked_index + 1);
        if (band->records.size() % m_record_bytes != 0)
            throw InputError(file, where, "size is not a whole number of paint records");
        band->record_count = band->records.size() / m_record_bytes;
        // Pixel indices strictly ascending within the band's rows: relight
        // writes each pixel from one record, so a corrupt index cannot write
        // outside the image or race with another record.
        const std::uint64_t first =
            static_cast<std::uint64_t>(band->first_row) * static_cast<std::uint64_t>(m_header.width);
        const std::uint64_t end =
            first + static_cast<std::uint64_t>(band->rows) * static_cast<std::uint64_t>(m_header.width);
        std::uint64_t previous = 0;
        for (std::size_t i = 0; i < band->record_count; ++i) {
            std::uint32_t pixel = 0;
            std::memcpy(&pixel, band->records.data() + i * m_record_bytes + RecordLayout::kPixel, 4);
            if (pixel < first || pixel >= end || (i > 0 && pixel <= previous))
                throw InputError(file, where + " > record " + std::to_string(i + 1),
                                 "pixel index " + std::to_string(pixel) +
                                     " is outside the band or out of order");
            previous = pixel;
        }
        m_bands[b] = std::move(band);
    });
    if (!m_bands[b])
        throw Error(m_impl->reader.path().string() + ": band " + std::to_string(index + 1) +
                    " failed to load");
    return *m_bands[b];
}

void RayMap::loadAll() const {
    tbb::parallel_for(0, bandCount(), [&](int b) { band(b); });
}

}  // namespace paintlab::raymaps
