#pragma once
// Where the workstation finds its demo data and keeps what it derives.

#include <QString>

#include <filesystem>

namespace paintlab::gui {

// The bundled demo scene (packaging/demo/scenes/car_body_sky.json).
std::filesystem::path demoScenePath();

// The ray map cached for a scene file: under the user's cache folder, named
// after the scene and a hash of its content, so an edited scene is traced anew,
// and `variant` ("-view960x512": the view box it was traced for, raymap_resolution.h).
std::filesystem::path cachedRayMapPath(const std::filesystem::path& scene, const QString& variant = {});

}  // namespace paintlab::gui
