#pragma once
// Private helpers of the text readers and writers: splitting lines into fields, strict number
// parsing and exact (shortest round-trip) number printing. Not part of the public API.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pena::io::detail {

// Splits `line` at runs of spaces, tabs, CR and LF; the views point into `line`.
std::vector<std::string_view> SplitWhitespace(std::string_view line);

// Splits at every `separator` (empty fields kept); the views point into `line`.
std::vector<std::string_view> SplitAt(std::string_view line, char separator);

// The whole field as a number ("nan" and "inf" included); nullopt if anything is left over.
std::optional<double> ParseDouble(std::string_view field);
std::optional<float> ParseFloat(std::string_view field);
std::optional<std::int64_t> ParseInt64(std::string_view field);

// Shortest fixed-point text that reads back to exactly `value` (no exponent).
std::string FormatExact(double value);
std::string FormatExact(float value);
// Fixed-point text with `decimals` digits after the point.
std::string FormatFixed(double value, int decimals);

}  // namespace pena::io::detail
