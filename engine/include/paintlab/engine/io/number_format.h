#pragma once
// Numbers as text, the same in every locale (std::to_chars, never printf or a
// stream's locale): one function for messages, files and tables, with the
// precision named by the caller.

#include <optional>
#include <string>
#include <string_view>

namespace paintlab::io {

enum class NumberFormat {
    // 6 significant digits, as printf("%g") and iostreams print by default:
    // messages, the BRDF table's CSV.
    Message,
    // 4 significant digits (printf "%.4g"): the CLI's recipe summaries.
    Brief,
    // The shortest text that reads back as the same double: data files (CSV, CGATS).
    Shortest,
    // 17 significant digits (printf "%.17g"): the GUI plots' CSV exports.
    Digits17,
};

std::string formatNumber(double value, NumberFormat format = NumberFormat::Message);

// The other way: a finite number written in any of these forms (std::from_chars;
// surrounding white space and a leading '+' allowed), nullopt for anything
// else: empty text, trailing characters, nan, inf, out of range. Never throws.
std::optional<double> parseFiniteNumber(std::string_view text);

// Fixed decimals (printf "%.*f") for text people read (production sheets);
// decimals is clamped to [0, 17].
std::string formatFixed(double value, int decimals);

// printf-style text (explanations with several numbers, such as the plan's
// reasons) in the C locale whatever the process's locale is (Qt sets the
// user's), and never truncated. The attribute lets the compiler check every
// call's arguments.
__attribute__((format(printf, 1, 2))) std::string formatText(const char* format, ...);

}  // namespace paintlab::io
