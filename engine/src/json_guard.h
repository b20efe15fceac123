#pragma once
// Reading untrusted JSON: a size cap checked before anything is read, a
// nesting-depth cap enforced while parsing, and parse errors turned into
// InputError messages with line, column and the field being read.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace paintlab::detail {

// Reads a whole file of at most max_bytes. Throws InputError naming the file
// if it is missing, unreadable, a directory, empty, or larger than max_bytes
// (checked from the file size, so a huge file is rejected without reading it).
std::string readBoundedTextFile(const std::filesystem::path& path, std::size_t max_bytes);

// Parses text as one JSON value, nesting at most max_depth. Throws InputError
// naming source, the line and column, and the last key before the error.
nlohmann::json parseUntrustedJson(std::string_view text, const std::string& source,
                                  std::size_t max_depth = 64);

}  // namespace paintlab::detail
