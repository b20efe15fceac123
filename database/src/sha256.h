#pragma once
// SHA-256 (FIPS 180-4) of a byte string, as 64 lowercase hex digits: the
// checksum of a recipe version's canonical JSON (computed by GNU Nettle).

#include <string>
#include <string_view>

namespace paintlab::db::detail {

std::string sha256Hex(std::string_view bytes);

}  // namespace paintlab::db::detail
