#pragma once
// The workstation's files go through the engine's one atomic writer
// (paintlab/engine/io/atomic_file.h): a crash or a full disk never leaves
// half an image or CSV where a good one was.

#include <QImage>
#include <QString>

#include <string_view>

namespace paintlab::gui {

// Writes bytes to path atomically; false (nothing changed) on any failure.
bool writeFileAtomically(const QString& path, std::string_view bytes);

// Encodes image in memory in the format its file suffix names (PNG when the
// suffix is none Qt writes) and writes it atomically; false on failure.
bool saveImageAtomically(const QImage& image, const QString& path);

}  // namespace paintlab::gui
