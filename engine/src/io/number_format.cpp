// Locale-independent number formatting (number_format.h).

#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <array>
#include <charconv>

namespace paintlab::io {

namespace {

// Large enough for any double in fixed notation with 17 decimals (309 digits before the point).
using Buffer = std::array<char, 352>;

std::string text(const Buffer& buffer, const std::to_chars_result& result) {
    if (result.ec != std::errc()) return {};
    return {buffer.data(), static_cast<std::size_t>(result.ptr - buffer.data())};
}

}  // namespace

std::string formatNumber(double value, NumberFormat format) {
    Buffer buffer{};
    char* const first = buffer.data();
    char* const last = buffer.data() + buffer.size();
    switch (format) {
    case NumberFormat::Message:
        return text(buffer, std::to_chars(first, last, value, std::chars_format::general, 6));
    case NumberFormat::Brief:
        return text(buffer, std::to_chars(first, last, value, std::chars_format::general, 4));
    case NumberFormat::Digits17:
        return text(buffer, std::to_chars(first, last, value, std::chars_format::general, 17));
    case NumberFormat::Shortest:
        break;
    }
    return text(buffer, std::to_chars(first, last, value));
}

std::string formatFixed(double value, int decimals) {
    Buffer buffer{};
    return text(buffer, std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                      std::chars_format::fixed, std::clamp(decimals, 0, 17)));
}

}  // namespace paintlab::io
