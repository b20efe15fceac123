#pragma once
// The one way PaintLab writes a file: the whole text goes to "<file>.tmp"
// beside it, which is then renamed over the file, so a reader never sees half
// a file and a failed write leaves the old one in place.

#include <filesystem>
#include <string_view>

namespace paintlab::io {

// Writes text (any bytes) to file atomically. Throws InputError naming the
// file if the temporary file cannot be created (a missing folder, no
// permission), Error naming the file if writing or the rename fails; the
// temporary file is removed on failure.
void writeFileAtomically(const std::filesystem::path& file, std::string_view text);

}  // namespace paintlab::io
