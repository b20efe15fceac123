// SHA-256 (FIPS 180-4) through GNU Nettle, Debian's nettle-dev: a kept,
// audited implementation instead of a hand-written one.

#include "sha256.h"

#include <nettle/sha2.h>

#include <array>
#include <cstdint>

namespace paintlab::db::detail {

std::string sha256Hex(std::string_view bytes) {
    sha256_ctx context{};
    sha256_init(&context);
    sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
    std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
    sha256_digest(&context, digest.size(), digest.data());
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(2 * digest.size());
    for (const std::uint8_t byte : digest) {
        out.push_back(kHex[byte >> 4U]);
        out.push_back(kHex[byte & 0x0fU]);
    }
    return out;
}

}  // namespace paintlab::db::detail
