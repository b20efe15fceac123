#include "file_output.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"

#include <QBuffer>
#include <QByteArray>
#include <QFileInfo>
#include <QImageWriter>

#include <cstddef>
#include <filesystem>

namespace paintlab::gui {

bool writeFileAtomically(const QString& path, std::string_view bytes) {
    try {
        io::writeFileAtomically(std::filesystem::path(path.toStdString()), bytes);
        return true;
    } catch (const Error&) {
        return false;
    }
}

bool saveImageAtomically(const QImage& image, const QString& path) {
    if (image.isNull()) return false;
    QByteArray format = QFileInfo(path).suffix().toLower().toLatin1();
    if (!QImageWriter::supportedImageFormats().contains(format)) format = "png";
    QByteArray encoded;
    QBuffer buffer(&encoded);
    if (!buffer.open(QIODevice::WriteOnly) || !image.save(&buffer, format.constData())) return false;
    return writeFileAtomically(
        path, std::string_view(encoded.constData(), static_cast<std::size_t>(encoded.size())));
}

}  // namespace paintlab::gui
