#pragma once
// The framing of ray-map files (docs/RAYMAPS.md, "File format"): a versioned
// header and a sequence of typed chunks, each with its length and a CRC-32 of
// its payload, closed by an end chunk that repeats the chunk count. Chunks
// are indexed when the file is opened (only their headers are read) and
// loaded on demand, their checksum verified then; a file that is truncated
// anywhere, has a corrupt chunk header or payload, the wrong magic or a
// newer version than this build reads is an InputError naming the file and
// the chunk, and nothing of it is trusted.
//
// Layout, little-endian:
//   header: magic (8 bytes), version (u32), reserved (u32)
//   chunk:  type (u32), reserved (u32), payload size (u64), payload CRC-32
//           (u32), CRC-32 of the preceding 20 bytes (u32), payload
//   end:    a chunk of type kEndChunk whose payload is the chunk count (u64)
//
// Writing goes through the engine's atomic writer (io/atomic_file.h): a
// temporary file renamed over FILE only by finish(), so a crash or a full
// disk never leaves a half-written file under the real name.

#include "paintlab/engine/io/atomic_file.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace paintlab::raymaps {

using Magic = std::array<char, 8>;

constexpr std::uint32_t chunkType(const char (&four)[5]) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(four[0])) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(four[1])) << 8U |
           static_cast<std::uint32_t>(static_cast<unsigned char>(four[2])) << 16U |
           static_cast<std::uint32_t>(static_cast<unsigned char>(four[3])) << 24U;
}
constexpr std::uint32_t kEndChunk = chunkType("END!");

// CRC-32 (zlib's, ISO 3309).
std::uint32_t crc32Of(std::span<const std::byte> data, std::uint32_t previous = 0);

class ChunkFileWriter {
public:
    ChunkFileWriter(std::filesystem::path path, const Magic& magic, std::uint32_t version);
    ~ChunkFileWriter() = default;  // the temporary file goes unless finish() succeeded
    ChunkFileWriter(const ChunkFileWriter&) = delete;
    ChunkFileWriter& operator=(const ChunkFileWriter&) = delete;
    ChunkFileWriter(ChunkFileWriter&&) = delete;
    ChunkFileWriter& operator=(ChunkFileWriter&&) = delete;

    void addChunk(std::uint32_t type, std::span<const std::byte> payload);
    // Writes the end chunk, flushes, renames into place. Throws Error on I/O failure.
    void finish();

private:
    void writeBytes(const void* data, std::size_t size);
    io::AtomicFileWriter m_file;
    std::uint64_t m_chunks = 0;
};

struct ChunkInfo {
    std::uint32_t type = 0;
    std::uint64_t offset = 0;  // of the payload in the file
    std::uint64_t size = 0;
    std::uint32_t crc = 0;
};

class ChunkFileReader {
public:
    // Reads and checks the header and every chunk header (not the payloads).
    ChunkFileReader(std::filesystem::path path, const Magic& magic, std::uint32_t max_version);

    std::uint32_t version() const { return m_version; }
    const std::vector<ChunkInfo>& chunks() const { return m_chunks; }
    // Index of the first chunk of this type, or -1.
    int find(std::uint32_t type) const;
    // Loads one payload and verifies its CRC.
    std::vector<std::byte> read(std::size_t chunk_index) const;
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
    std::uint32_t m_version = 0;
    std::vector<ChunkInfo> m_chunks;
};

std::string chunkTypeName(std::uint32_t type);

}  // namespace paintlab::raymaps
