#pragma once
// What the ray-map builder and reader share: the magic, the chunk types and
// the header's JSON form.

#include "paintlab/raymaps/chunk_file.h"
#include "paintlab/raymaps/raymap.h"

#include <string>

namespace paintlab::raymaps {

constexpr Magic kRayMapMagic{'P', 'L', 'R', 'A', 'Y', 'M', 'A', 'P'};
// 2: the header holds the camera (position, pixel angle) and the scene unit.
// Version 1 is still read (RayMapHeader's defaults).
constexpr std::uint32_t kRayMapVersion = 2;
constexpr std::uint32_t kHeaderChunk = chunkType("HEAD");
constexpr std::uint32_t kBakedChunk = chunkType("BAKE");
constexpr std::uint32_t kPaintChunk = chunkType("PNTR");

std::string headerToJson(const RayMapHeader& header);

}  // namespace paintlab::raymaps
