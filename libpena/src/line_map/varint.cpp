#include "varint.hpp"

namespace pena::line_map {

void ByteWriter::PutVarint(std::uint64_t value) {
  while (value >= 0x80U) {
    bytes_.push_back(static_cast<char>((value & 0x7FU) | 0x80U));
    value >>= 7;
  }
  bytes_.push_back(static_cast<char>(value));
}

void ByteWriter::PutString(std::string_view text) {
  PutVarint(text.size());
  bytes_.append(text);
}

std::uint64_t ByteReader::GetVarint() {
  if (failed()) return 0;
  std::uint64_t value = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (position_ >= bytes_.size()) {
      Fail("truncated varint");
      return 0;
    }
    const auto byte = static_cast<std::uint8_t>(bytes_[position_++]);
    // The tenth byte may only hold the top bit of a 64-bit value.
    if (shift == 63 && byte > 1U) break;
    value |= static_cast<std::uint64_t>(byte & 0x7FU) << shift;
    if ((byte & 0x80U) == 0) return value;
  }
  Fail("overlong varint");
  return 0;
}

std::string ByteReader::GetString() {
  const std::uint64_t size = GetVarint();
  if (failed()) return {};
  if (size > remaining()) {
    Fail("string of " + std::to_string(size) + " bytes past the end");
    return {};
  }
  std::string text(bytes_.substr(position_, static_cast<std::size_t>(size)));
  position_ += static_cast<std::size_t>(size);
  return text;
}

std::uint64_t ByteReader::GetCount(std::size_t min_bytes) {
  const std::uint64_t count = GetVarint();
  if (failed()) return 0;
  if (min_bytes > 0 && count > remaining() / min_bytes) {
    Fail("count " + std::to_string(count) + " exceeds the " + std::to_string(remaining()) +
         " bytes left");
    return 0;
  }
  return count;
}

void ByteReader::Fail(const std::string& why) {
  if (error_.empty()) error_ = "byte " + std::to_string(position_) + ": " + why;
}

}  // namespace pena::line_map
