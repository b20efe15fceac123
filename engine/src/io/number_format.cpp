// Locale-independent number formatting (number_format.h).

#include "paintlab/engine/io/number_format.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <clocale>  // with glibc also POSIX newlocale, uselocale
#include <cmath>
#include <cstdarg>
#include <cstdio>

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

std::string formatText(const char* format, ...) {
    // One C locale for the process, made on first use (newlocale is thread-safe);
    // uselocale changes only this thread's locale, and only until the end of the call.
    static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", nullptr);
    const locale_t previous = uselocale(c_locale);
    va_list args;
    va_start(args, format);
    va_list again;
    va_copy(again, args);
    const int size = std::vsnprintf(nullptr, 0, format, args);
    std::string out(size > 0 ? static_cast<std::size_t>(size) : 0U, '\0');
    if (size > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
    va_end(again);
    va_end(args);
    uselocale(previous);
    return out;
}

std::optional<double> parseFiniteNumber(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())) != 0)
        text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())) != 0) text.remove_suffix(1);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

}  // namespace paintlab::io
