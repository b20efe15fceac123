// Temporary file and rename (atomic_file.h).

#include "paintlab/engine/io/atomic_file.h"

#include "paintlab/engine/error.h"

#include <fstream>
#include <string>
#include <system_error>

namespace paintlab::io {

void writeFileAtomically(const std::filesystem::path& file, std::string_view text) {
    std::filesystem::path temp = file;
    temp += ".tmp";
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw InputError(file.string(), "",
                             "cannot open for writing (temporary file " + temp.string() + ")");
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.flush();
        if (!out) {
            out.close();
            std::error_code ignored;
            std::filesystem::remove(temp, ignored);
            throw Error(file.string() + ": writing failed (disk full?)");
        }
    }
    std::error_code error;
    std::filesystem::rename(temp, file, error);
    if (error) {
        const std::string reason = error.message();
        std::filesystem::remove(temp, error);
        throw Error(file.string() + ": cannot replace the file: " + reason);
    }
}

}  // namespace paintlab::io
