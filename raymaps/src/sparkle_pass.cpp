// The sparkle pass over the paint records (sparkle_pass.h).

#include "paintlab/raymaps/sparkle_pass.h"

#include "record_layout.h"
#include "sampling.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/sparkle/sparkle_texture.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <string>

namespace paintlab::raymaps {

namespace {

void checkSetting(double value, bool zero_ok, const char* name) {
    if (!std::isfinite(value) || value < 0.0 || (!zero_ok && value == 0.0))
        throw InputError("<argument>", name,
                         std::to_string(value) + (zero_ok ? " must be >= 0" : " must be > 0"));
}

}  // namespace

SparklePassStats addSparkle(const RayMap& map, const SparkleModel& model, RgbImage& image,
                            const SparklePassSettings& settings) {
    const RayMapHeader& h = map.header();
    const double scene_unit_m = settings.scene_unit_m.value_or(h.scene_unit_m);
    const double pixel_angle_rad = settings.pixel_angle_rad.value_or(h.pixel_angle_rad);
    checkSetting(scene_unit_m, false, "scene_unit_m");
    checkSetting(pixel_angle_rad, true, "pixel_angle_rad");
    checkSetting(settings.viewing_distance_m, false, "viewing_distance_m");
    checkSetting(settings.aperture_mm, false, "aperture_mm");
    if (image.width != h.width || image.height != h.height ||
        image.rgb.size() != static_cast<std::size_t>(h.width) * static_cast<std::size_t>(h.height) * 3)
        throw InputError(map.path().string(), "image",
                         "the image is " + std::to_string(image.width) + " x " +
                             std::to_string(image.height) + ", the map " + std::to_string(h.width) + " x " +
                             std::to_string(h.height));
    const auto start = std::chrono::steady_clock::now();
    SparklePassStats stats;
    if (!model.hasFlakes() || h.lights.empty()) return stats;

    // Linear sRGB weights of the model's bands (colour/band_weights.h).
    const auto wavelengths = model.wavelengthsNm();
    const std::size_t bands = wavelengths.size();
    std::vector<Rgb3> weights(bands, Rgb3::Zero());
    if (bands >= 2) {
        const BandColourWeights colours = bandColourWeights(wavelengths);
        for (std::size_t b = 0; b < bands; ++b) {
            const Rgb& c = colours.linear_srgb[b];
            weights[b] = Rgb3(c.r, c.g, c.b);
        }
    } else {
        weights[0] = Rgb3::Ones();  // one band: grey
    }

    const RecordLayout layout{h.cells, h.orders, static_cast<int>(h.lights.size())};
    const std::size_t stride = layout.bytes();
    const double unit_um = scene_unit_m * 1e6;
    std::atomic<std::uint64_t> pixels{0};
    std::atomic<std::uint64_t> glint_pixels{0};
    std::atomic<std::uint64_t> glints_micro{0};  // sum of Poisson means x 1e6
    std::atomic<std::uint64_t> light_visits{0};

    tbb::parallel_for(0, map.bandCount(), [&](int b) {
        const RayMapBand& band = map.band(b);
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, band.record_count, 64),
            [&](const tbb::blocked_range<std::size_t>& range) {
                std::vector<double> x;
                SparkleStats s;  // reused: no allocation per pixel
                std::uint64_t local_glint_pixels = 0;
                std::uint64_t local_visits = 0;
                double local_glints = 0.0;
                for (std::size_t r = range.begin(); r != range.end(); ++r) {
                    const std::byte* rec = band.records.data() + r * stride;
                    const auto pixel = recordField<std::uint32_t>(rec + RecordLayout::kPixel);
                    const Vec3 n = recordDirection(rec + RecordLayout::kNormal);
                    const Vec3 v = recordDirection(rec + RecordLayout::kView);
                    const double mu_o = n.dot(v);
                    if (!(mu_o > 1e-3)) continue;
                    const Vec3 position(
                        static_cast<double>(recordField<float>(rec + RecordLayout::kPosition)),
                        static_cast<double>(recordField<float>(rec + RecordLayout::kPosition + 4)),
                        static_cast<double>(recordField<float>(rec + RecordLayout::kPosition + 8)));
                    const double footprint_um =
                        static_cast<double>(recordHalf(rec + RecordLayout::kFootprint)) * unit_um;
                    if (!(footprint_um > 0.0)) continue;
                    const Rgb3 weight(static_cast<double>(recordHalf(rec + RecordLayout::kWeight)),
                                      static_cast<double>(recordHalf(rec + RecordLayout::kWeight + 2)),
                                      static_cast<double>(recordHalf(rec + RecordLayout::kWeight + 4)));
                    // The texture's frame from the normal alone: it must not turn with the view.
                    const Frame frame = Frame::fromNormal(n);
                    const Vec3 wo = frame.toLocal(v);
                    const double distance_m = pixel_angle_rad > 0.0 ? footprint_um * 1e-6 / pixel_angle_rad
                                                                    : settings.viewing_distance_m;
                    SparkleGeometry g;
                    g.wo = {wo.x(), wo.y(), wo.z()};
                    g.element_area_um2 = footprint_um * footprint_um / mu_o;
                    g.view_solid_angle_sr = viewApertureSr(distance_m, settings.aperture_mm);
                    const std::uint64_t key =
                        sparkleCellKey(position.x() * unit_um, position.y() * unit_um, position.z() * unit_um,
                                       std::sqrt(g.element_area_um2), settings.seed);
                    Rgb3 add = Rgb3::Zero();
                    bool glint = false;
                    for (std::size_t k = 0; k < h.lights.size(); ++k) {
                        const auto vis = recordField<std::uint8_t>(rec + layout.visibility() + k);
                        if (vis == 0) continue;
                        const ExplicitLight& light = h.lights[k];
                        Vec3 wi = light.vector;
                        Rgb3 e = light.power;
                        if (light.kind == ExplicitLight::Kind::Point) {
                            wi -= position;
                            const double r2 = wi.squaredNorm();
                            if (!(r2 > 0.0)) continue;
                            wi /= std::sqrt(r2);
                            e /= r2;
                        }
                        const Vec3 wl = frame.toLocal(wi);
                        if (!(wl.z() > 0.0)) continue;
                        g.wi = {wl.x(), wl.y(), wl.z()};
                        g.light_solid_angle_sr = light.solid_angle_sr;
                        model.evaluate(g, s);
                        ++local_visits;
                        local_glints += s.expected_glints;
                        x.assign(s.terms.size(), 0.0);
                        drawSparkle(s, key, x);
                        Rgb3 f = Rgb3::Zero();
                        for (std::size_t t = 0; t < x.size(); ++t) {
                            if (x[t] > -1.0) glint = glint || s.terms[t].mean_glints > 0.0;
                            for (std::size_t c = 0; c < bands; ++c)
                                f += (s.terms[t].flake_brdf_per_sr[c] * x[t]) * weights[c];
                        }
                        add += (static_cast<double>(vis) / 255.0 * wl.z()) * f.cwiseProduct(e);
                    }
                    if (glint) ++local_glint_pixels;
                    float* px = image.rgb.data() + 3 * static_cast<std::size_t>(pixel);
                    for (int c = 0; c < 3; ++c) px[c] += static_cast<float>(weight[c] * add[c]);
                }
                pixels += range.size();
                glint_pixels += local_glint_pixels;
                light_visits += local_visits;
                glints_micro += static_cast<std::uint64_t>(std::min(local_glints, 1e12) * 1e6);
            });
    });
    stats.pixels = pixels.load();
    stats.glint_pixels = glint_pixels.load();
    const auto visits = light_visits.load();
    stats.mean_glints =
        visits > 0 ? static_cast<double>(glints_micro.load()) * 1e-6 / static_cast<double>(visits) : 0.0;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

}  // namespace paintlab::raymaps
