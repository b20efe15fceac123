#pragma once
// The sparkle pass (issue 7): after relight(), one more pass over the paint
// records adds the zero-mean sparkle radiance of every explicit light
// (sparkle_texture.h):
//
//   pixel += weight * sum_k V_k E_k mu_i,k * RGB(sum_t f_t (X_t - 1)),
//
// so the relit image's mean over many pixels is unchanged and relight.cpp's
// kernel is untouched. Per pixel it needs what the records already hold:
// position (the texture's key), shading normal (the texture's frame, built
// from the normal alone so that it does not turn with the view), view
// direction, footprint (the surface element), weight and light visibility;
// and per light the header's direction, irradiance and solid angle.
//
// The footprint is in scene units; the paint's flakes are in µm: the scene's
// unit comes from the map's header (version 2; scene.h says lengths are in
// scene units, the demo's are metres) unless the settings give one. The view
// aperture (the eye's pupil) needs the distance to the camera, which the
// records do not store: footprint / pixel angle (the header's, or the
// settings'), else (a version-1 map) a fixed viewing distance.

#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"

#include <cstdint>
#include <optional>

namespace paintlab::raymaps {

struct SparklePassSettings {
    std::optional<double> scene_unit_m;  // one scene unit in metres; unset: the map's (1 for version 1)
    // The camera's, 2 tan(fov / 2) / height; unset: the map's; 0 (or a
    // version-1 map's unknown angle): use viewing_distance_m.
    std::optional<double> pixel_angle_rad;
    double viewing_distance_m = 2.0;  // when the pixel angle is not known
    double aperture_mm = 3.0;         // the viewer's pupil (daylight)
    std::uint64_t seed = 0;           // another texture for the same surface
};

struct SparklePassStats {
    std::uint64_t pixels = 0;        // paint pixels visited
    std::uint64_t glint_pixels = 0;  // pixels whose draw held at least one glint (any light)
    double mean_glints = 0.0;        // mean Poisson mean per pixel and light
    double seconds = 0.0;
};

// Adds the sparkle radiance to `image` (the relight of `map`, same size).
// Throws InputError if the image's size differs from the map's or a setting
// is out of range (scene_unit_m, aperture_mm, viewing_distance_m > 0,
// pixel_angle_rad >= 0), naming the setting; InputError from the map's bands.
SparklePassStats addSparkle(const RayMap& map, const SparkleModel& model, RgbImage& image,
                            const SparklePassSettings& settings = {});

}  // namespace paintlab::raymaps
