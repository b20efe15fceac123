// The ray-map file framing: round trip, and every truncation and every
// single-byte corruption detected and named, never trusted.

#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/chunk_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

namespace paintlab::raymaps {
namespace {

constexpr Magic kMagic = {'P', 'L', 'T', 'E', 'S', 'T', '0', '1'};
constexpr std::uint32_t kImage = chunkType("IMAG");
constexpr std::uint32_t kPaint = chunkType("PNT0");

std::vector<std::byte> pattern(std::size_t n, int seed) {
    std::vector<std::byte> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = static_cast<std::byte>((i * 131 + static_cast<std::size_t>(seed)) & 0xFFU);
    return v;
}

std::filesystem::path writeSample(const test::TempDir& dir) {
    const auto file = dir.path() / "sample.prm";
    ChunkFileWriter writer(file, kMagic, 1);
    writer.addChunk(kImage, pattern(300, 1));
    writer.addChunk(kPaint, pattern(77, 2));
    writer.addChunk(kPaint, {});
    writer.finish();
    return file;
}

std::vector<char> bytesOf(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::filesystem::path& file, const std::vector<char>& bytes) {
    std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Opens and loads every chunk, as a consumer would.
void loadAll(const std::filesystem::path& file) {
    const ChunkFileReader reader(file, kMagic, 1);
    for (std::size_t i = 0; i < reader.chunks().size(); ++i) (void)reader.read(i);
}

TEST(ChunkFile, RoundTrip) {
    const test::TempDir dir;
    const auto file = writeSample(dir);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{file.filename().string()});  // no temporary left
    const ChunkFileReader reader(file, kMagic, 1);
    ASSERT_EQ(reader.chunks().size(), 3U);
    EXPECT_EQ(reader.find(kPaint), 1);
    EXPECT_EQ(reader.find(chunkType("NONE")), -1);
    EXPECT_EQ(reader.read(0), pattern(300, 1));
    EXPECT_EQ(reader.read(1), pattern(77, 2));
    EXPECT_TRUE(reader.read(2).empty());
}

TEST(ChunkFile, Crc32MatchesTheStandardCheckValue) {
    // The CRC-32 check value of "123456789" (ISO 3309 / ITU-T V.42): 0xCBF43926.
    const std::string text = "123456789";
    EXPECT_EQ(crc32Of(std::as_bytes(std::span(text.data(), text.size()))), 0xCBF43926U);
}

TEST(ChunkFile, EveryTruncationIsDetected) {
    const test::TempDir dir;
    const auto bytes = bytesOf(writeSample(dir));
    const auto cut = dir.path() / "cut.prm";
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        writeBytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n)));
        try {
            loadAll(cut);
            FAIL() << "accepted the file cut at " << n << " of " << bytes.size() << " bytes";
        } catch (const InputError& e) {
            ASSERT_NE(std::string(e.what()).find("cut.prm"), std::string::npos) << e.what();
        }
    }
}

TEST(ChunkFile, EverySingleByteCorruptionIsDetected) {
    const test::TempDir dir;
    const auto bytes = bytesOf(writeSample(dir));
    const auto bad = dir.path() / "bad.prm";
    int payload_errors = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        std::vector<char> changed = bytes;
        changed[i] = static_cast<char>(changed[i] ^ 0x20);
        writeBytes(bad, changed);
        try {
            loadAll(bad);
            FAIL() << "accepted the file with byte " << i << " changed";
        } catch (const InputError& e) {
            const std::string what = e.what();
            ASSERT_NE(what.find("bad.prm"), std::string::npos) << what;
            payload_errors += what.find("corrupt chunk (checksum") != std::string::npos ? 1 : 0;
        }
    }
    EXPECT_EQ(payload_errors, 300 + 77);  // every payload byte is caught by its chunk's CRC
}

TEST(ChunkFile, WrongMagicNewerVersionAndMissingFile) {
    const test::TempDir dir;
    const auto file = writeSample(dir);
    constexpr Magic other = {'N', 'O', 'T', 'A', 'M', 'A', 'P', '!'};
    EXPECT_THROW(ChunkFileReader(file, other, 1), InputError);
    {
        ChunkFileWriter writer(dir.path() / "v2.prm", kMagic, 2);
        writer.finish();
    }
    try {
        const ChunkFileReader reader(dir.path() / "v2.prm", kMagic, 1);
        FAIL() << "read a newer version";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("format version 2"), std::string::npos) << e.what();
    }
    EXPECT_THROW(ChunkFileReader(dir.path() / "absent.prm", kMagic, 1), InputError);
}

TEST(ChunkFile, AnUnfinishedWriterLeavesNothingBehind) {
    const test::TempDir dir;
    const auto file = dir.path() / "unfinished.prm";
    {
        ChunkFileWriter writer(file, kMagic, 1);
        writer.addChunk(kImage, pattern(10, 3));
        // destroyed without finish(), as when precompute is cancelled
    }
    EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace paintlab::raymaps
