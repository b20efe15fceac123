#include "paintlab/raymaps/chunk_file.h"

#include "paintlab/engine/error.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

namespace paintlab::raymaps {

static_assert(std::endian::native == std::endian::little,
              "ray-map files are little-endian; add byte swapping");

namespace {

constexpr std::size_t kHeaderBytes = 16;
constexpr std::size_t kChunkHeaderBytes = 24;

struct ChunkHeader {
    std::uint32_t type = 0;
    std::uint32_t reserved = 0;
    std::uint64_t size = 0;
    std::uint32_t crc = 0;
};

std::array<std::byte, kChunkHeaderBytes> encode(const ChunkHeader& h) {
    std::array<std::byte, kChunkHeaderBytes> bytes{};
    std::memcpy(bytes.data(), &h.type, 4);
    std::memcpy(bytes.data() + 4, &h.reserved, 4);
    std::memcpy(bytes.data() + 8, &h.size, 8);
    std::memcpy(bytes.data() + 16, &h.crc, 4);
    const std::uint32_t header_crc = crc32Of(std::span(bytes).first(20));
    std::memcpy(bytes.data() + 20, &header_crc, 4);
    return bytes;
}

}  // namespace

std::uint32_t crc32Of(std::span<const std::byte> data, std::uint32_t previous) {
    uLong crc = previous;
    // zlib takes at most uInt bytes per call.
    constexpr std::size_t kStep = std::numeric_limits<uInt>::max() / 2;
    for (std::size_t at = 0; at < data.size(); at += kStep) {
        const std::size_t n = std::min(kStep, data.size() - at);
        crc = ::crc32(crc, reinterpret_cast<const Bytef*>(data.data() + at), static_cast<uInt>(n));
    }
    return static_cast<std::uint32_t>(crc);
}

std::string chunkTypeName(std::uint32_t type) {
    std::string name;
    for (int i = 0; i < 4; ++i) {
        const auto c = static_cast<char>((type >> (8U * static_cast<unsigned>(i))) & 0xFFU);
        name += (c >= 32 && c < 127) ? c : '?';
    }
    return name;
}

// ---- writer ----

ChunkFileWriter::ChunkFileWriter(std::filesystem::path path, const Magic& magic, std::uint32_t version)
    : m_file(std::move(path)) {
    writeBytes(magic.data(), magic.size());
    const std::uint32_t reserved = 0;
    writeBytes(&version, 4);
    writeBytes(&reserved, 4);
}

void ChunkFileWriter::writeBytes(const void* data, std::size_t size) { m_file.write(data, size); }

void ChunkFileWriter::addChunk(std::uint32_t type, std::span<const std::byte> payload) {
    const ChunkHeader header{type, 0, payload.size(), crc32Of(payload)};
    const auto bytes = encode(header);
    writeBytes(bytes.data(), bytes.size());
    writeBytes(payload.data(), payload.size());
    ++m_chunks;
}

void ChunkFileWriter::finish() {
    const std::uint64_t count = m_chunks;
    addChunk(kEndChunk, std::as_bytes(std::span(&count, 1)));
    m_file.commit();
}

// ---- reader ----

ChunkFileReader::ChunkFileReader(std::filesystem::path path, const Magic& magic, std::uint32_t max_version)
    : m_path(std::move(path)) {
    const std::string name = m_path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(m_path, ec)) throw InputError(name, "", "file not found");
    const std::uint64_t file_size = std::filesystem::file_size(m_path, ec);
    if (ec) throw InputError(name, "", "cannot read the file size: " + ec.message());
    std::ifstream in(m_path, std::ios::binary);
    if (!in) throw InputError(name, "", "cannot open for reading");

    std::array<char, kHeaderBytes> header{};
    if (file_size < kHeaderBytes || !in.read(header.data(), kHeaderBytes))
        throw InputError(name, "header", "file is shorter than the header (truncated)");
    if (!std::equal(magic.begin(), magic.end(), header.begin()))
        throw InputError(name, "header",
                         "not a " + std::string(magic.data(), magic.size()) + " file (wrong magic)");
    std::memcpy(&m_version, header.data() + 8, 4);
    std::uint32_t reserved = 0;
    std::memcpy(&reserved, header.data() + 12, 4);
    if (reserved != 0) throw InputError(name, "header", "corrupt header (reserved field is not zero)");
    if (m_version == 0 || m_version > max_version)
        throw InputError(name, "header",
                         "format version " + std::to_string(m_version) + "; this build reads versions 1 to " +
                             std::to_string(max_version) + " (rebuild the file or update PaintLab)");

    std::uint64_t at = kHeaderBytes;
    for (;;) {
        const std::string where = "chunk " + std::to_string(m_chunks.size() + 1);
        if (file_size - at < kChunkHeaderBytes)
            throw InputError(name, where, "file ends inside the chunk header (truncated)");
        std::array<std::byte, kChunkHeaderBytes> bytes{};
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(bytes.data()), kChunkHeaderBytes))
            throw InputError(name, where, "cannot read the chunk header");
        ChunkHeader h;
        std::uint32_t header_crc = 0;
        std::memcpy(&h.type, bytes.data(), 4);
        std::memcpy(&h.reserved, bytes.data() + 4, 4);
        std::memcpy(&h.size, bytes.data() + 8, 8);
        std::memcpy(&h.crc, bytes.data() + 16, 4);
        std::memcpy(&header_crc, bytes.data() + 20, 4);
        if (crc32Of(std::span(bytes).first(20)) != header_crc)
            throw InputError(name, where, "corrupt chunk header (checksum mismatch)");
        at += kChunkHeaderBytes;
        if (h.size > file_size - at)
            throw InputError(name, where + " (" + chunkTypeName(h.type) + ")",
                             "chunk of " + std::to_string(h.size) +
                                 " bytes runs past the end of the file (truncated)");
        if (h.type == kEndChunk) {
            std::uint64_t count = 0;
            if (h.size != 8) throw InputError(name, where + " (end)", "malformed end chunk");
            in.seekg(static_cast<std::streamoff>(at));
            in.read(reinterpret_cast<char*>(&count), 8);
            if (!in || crc32Of(std::as_bytes(std::span(&count, 1))) != h.crc || count != m_chunks.size())
                throw InputError(name, where + " (end)",
                                 "end chunk does not match the chunks read (corrupt)");
            if (at + 8 != file_size) throw InputError(name, "", "unexpected bytes after the end chunk");
            break;
        }
        m_chunks.push_back({h.type, at, h.size, h.crc});
        at += h.size;
    }
}

int ChunkFileReader::find(std::uint32_t type) const {
    for (std::size_t i = 0; i < m_chunks.size(); ++i)
        if (m_chunks[i].type == type) return static_cast<int>(i);
    return -1;
}

std::vector<std::byte> ChunkFileReader::read(std::size_t chunk_index) const {
    const ChunkInfo& c = m_chunks.at(chunk_index);
    const std::string where = "chunk " + std::to_string(chunk_index + 1) + " (" + chunkTypeName(c.type) + ")";
    std::ifstream in(m_path, std::ios::binary);
    std::vector<std::byte> payload(c.size);
    in.seekg(static_cast<std::streamoff>(c.offset));
    if (!in || !in.read(reinterpret_cast<char*>(payload.data()), static_cast<std::streamsize>(c.size)))
        throw InputError(m_path.string(), where,
                         "cannot read the chunk (file changed or truncated since it was opened)");
    if (crc32Of(payload) != c.crc)
        throw InputError(m_path.string(), where, "corrupt chunk (checksum mismatch)");
    return payload;
}

}  // namespace paintlab::raymaps
