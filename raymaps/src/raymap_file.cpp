// Reading ray-map files: the header (JSON) checked field by field, the bands
// read and checked on first use.

#include "raymap_io.h"
#include "record_layout.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/raymap.h"

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>

namespace paintlab::raymaps {

namespace {

using nlohmann::json;

constexpr int kMaxImageSide = 16384;

json vec3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

class HeaderReader {
public:
    explicit HeaderReader(std::string file) : m_file(std::move(file)) {}
    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throw InputError(m_file, "chunk 1 (HEAD) > " + field, message);
    }
    const json& at(const json& object, const std::string& key, const std::string& path) const {
        if (!object.is_object() || !object.contains(key)) fail(path, "missing");
        return object.at(key);
    }
    double number(const json& object, const std::string& key, double low, double high,
                  const std::string& path) const {
        const json& v = at(object, key, path);
        if (!v.is_number()) fail(path, "not a number");
        const double x = v.get<double>();
        if (!(x >= low && x <= high))
            fail(path, std::to_string(x) + " is outside [" + std::to_string(low) + ", " +
                           std::to_string(high) + "]");
        return x;
    }
    int integer(const json& object, const std::string& key, int low, int high,
                const std::string& path) const {
        const json& v = at(object, key, path);
        if (!v.is_number_integer()) fail(path, "not an integer");
        const auto x = v.get<std::int64_t>();
        if (x < low || x > high)
            fail(path, std::to_string(x) + " is outside [" + std::to_string(low) + ", " +
                           std::to_string(high) + "]");
        return static_cast<int>(x);
    }
    Eigen::Vector3d vector(const json& object, const std::string& key, const std::string& path) const {
        const json& v = at(object, key, path);
        if (!v.is_array() || v.size() != 3) fail(path, "not an array of 3 numbers");
        Eigen::Vector3d out;
        for (std::size_t i = 0; i < 3; ++i) {
            if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
                fail(path, "not an array of 3 numbers");
            out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
        }
        return out;
    }

private:
    std::string m_file;
};

RayMapHeader parseHeader(const std::vector<std::byte>& payload, const std::string& file) {
    json j;
    try {
        j = json::parse(reinterpret_cast<const char*>(payload.data()),
                        reinterpret_cast<const char*>(payload.data()) + payload.size());
    } catch (const json::exception& e) {
        throw InputError(file, "chunk 1 (HEAD)", std::string("header is not valid JSON: ") + e.what());
    }
    const HeaderReader r(file);
    RayMapHeader h;
    h.width = r.integer(j, "width", 1, kMaxImageSide, "width");
    h.height = r.integer(j, "height", 1, kMaxImageSide, "height");
    h.cells = r.integer(j, "cells", 1, 16, "cells");
    h.orders = r.integer(j, "orders", 1, 16, "orders");
    h.band_rows = r.integer(j, "band_rows", 1, 4096, "band_rows");
    h.env_lights = r.integer(j, "env_lights", 0, 255, "env_lights");
    h.paint_proxy_albedo = r.number(j, "paint_proxy_albedo", 0.0, 1.0, "paint_proxy_albedo");
    const json& scene = r.at(j, "scene_file", "scene_file");
    if (!scene.is_string()) r.fail("scene_file", "not a string");
    h.scene_file = scene.get<std::string>();
    const json& lights = r.at(j, "lights", "lights");
    if (!lights.is_array() || lights.size() > 255) r.fail("lights", "not an array of at most 255 lights");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::string path = "lights > light " + std::to_string(i + 1);
        const json& l = lights[i];
        ExplicitLight light;
        const json& kind = r.at(l, "kind", path + " > kind");
        if (kind == "sun") {
            light.kind = ExplicitLight::Kind::Sun;
        } else if (kind == "point") {
            light.kind = ExplicitLight::Kind::Point;
        } else {
            r.fail(path + " > kind", "not 'sun' or 'point'");
        }
        light.vector = r.vector(l, "vector", path + " > vector");
        light.power = r.vector(l, "power", path + " > power");
        light.solid_angle_sr =
            r.number(l, "solid_angle_sr", 0.0, 4.0 * 3.14159266, path + " > solid_angle_sr");
        if (light.kind == ExplicitLight::Kind::Sun) {
            if (std::abs(light.vector.norm() - 1.0) > 1e-6)
                r.fail(path + " > vector", "not a unit direction");
        }
        h.lights.push_back(light);
    }
    const json& stats = r.at(j, "statistics", "statistics");
    h.paint_pixels =
        static_cast<std::uint64_t>(r.number(stats, "paint_pixels", 0.0, 1e12, "statistics > paint_pixels"));
    h.rays = static_cast<std::uint64_t>(r.number(stats, "rays", 0.0, 1e18, "statistics > rays"));
    h.seconds = r.number(stats, "seconds", 0.0, 1e9, "statistics > seconds");
    const int record = r.integer(j, "record_bytes", 1, 1 << 20, "record_bytes");
    if (static_cast<std::size_t>(record) != recordBytes(h.cells, h.orders, static_cast<int>(h.lights.size())))
        r.fail("record_bytes", "does not match the layout of version 1 for these cells, orders and lights");
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
    map->m_header = parseHeader(reader.read(0), file);
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
