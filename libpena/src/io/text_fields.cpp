#include "text_fields.hpp"

#include <array>
#include <charconv>
#include <cstdio>
#include <system_error>

namespace pena::io::detail {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// from_chars rejects a leading '+', which some writers emit; accept it once.
std::string_view StripPlus(std::string_view field) {
  if (field.size() > 1 && field.front() == '+' && field[1] != '-') field.remove_prefix(1);
  return field;
}

template <typename T>
std::optional<T> ParseWhole(std::string_view field) {
  field = StripPlus(field);
  if (field.empty()) return std::nullopt;
  T value{};
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return value;
}

template <typename T>
std::string ToCharsFixed(T value) {
  std::array<char, 400> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed);
  if (result.ec != std::errc()) {
    // Only reachable for huge magnitudes: fall back to the exponent form, still exact.
    const auto general = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), general.ptr);
  }
  return std::string(buffer.data(), result.ptr);
}

}  // namespace

std::vector<std::string_view> SplitWhitespace(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

std::vector<std::string_view> SplitAt(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    if (end == std::string_view::npos) {
      fields.push_back(line.substr(start));
      return fields;
    }
    fields.push_back(line.substr(start, end - start));
    start = end + 1;
  }
}

std::optional<double> ParseDouble(std::string_view field) { return ParseWhole<double>(field); }
std::optional<float> ParseFloat(std::string_view field) { return ParseWhole<float>(field); }
std::optional<std::int64_t> ParseInt64(std::string_view field) {
  return ParseWhole<std::int64_t>(field);
}

std::string FormatExact(double value) { return ToCharsFixed(value); }
std::string FormatExact(float value) { return ToCharsFixed(value); }

std::string FormatFixed(double value, int decimals) {
  std::array<char, 400> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return ToCharsFixed(value);
  return std::string(buffer.data(), result.ptr);
}

}  // namespace pena::io::detail
