#pragma once
// The one way PaintLab writes a file: the bytes go to a temporary file beside
// it, which is flushed to disk and then renamed over the file, so a reader
// never sees half a file and a failed write or a crash leaves the old one in
// place.

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace paintlab::io {

// A file written in pieces (a ray map, chunk by chunk) and put in place by
// commit(). Destroying it without commit() removes the temporary file.
class AtomicFileWriter {
public:
    // Creates the temporary file "<file>.tmp-<pid>-<n>". Throws InputError
    // naming file if it cannot be created (a missing folder, no permission).
    explicit AtomicFileWriter(std::filesystem::path file);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
    AtomicFileWriter(AtomicFileWriter&&) = delete;
    AtomicFileWriter& operator=(AtomicFileWriter&&) = delete;

    // Throws Error naming the file if writing fails (disk full).
    void write(const void* data, std::size_t size);
    void write(std::string_view bytes) { write(bytes.data(), bytes.size()); }
    // fsync, close, rename over the file, fsync its folder. Throws Error
    // naming the file on failure (the old file is then untouched).
    void commit();

    const std::filesystem::path& file() const { return m_file; }

private:
    void discard() noexcept;
    std::filesystem::path m_file;
    std::filesystem::path m_temp;
    int m_fd = -1;
    bool m_committed = false;
};

// Writes bytes (any, not only text) to file atomically, as AtomicFileWriter.
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes);

}  // namespace paintlab::io
