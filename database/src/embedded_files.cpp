// Joins the chunks of the embedded files (embedded_files.h).

#include "embedded_files.h"

namespace paintlab::db::detail {

std::vector<EmbeddedFile> joinChunks(std::initializer_list<EmbeddedChunks> files) {
    std::vector<EmbeddedFile> out;
    out.reserve(files.size());
    for (const auto& file : files) {
        EmbeddedFile joined{std::string(file.name), {}};
        for (const std::string_view chunk : file.chunks) joined.text.append(chunk);
        out.push_back(std::move(joined));
    }
    return out;
}

}  // namespace paintlab::db::detail
