#pragma once
// LEB128 varints and zig-zag signed integers for the map packing (map_packing.hpp). The reader is
// bounds-checked: past the end or on an overlong varint it fails once and returns zeros after.

#include <cstdint>
#include <string>
#include <string_view>

namespace pena::line_map {

// Zig-zag maps small magnitudes of either sign to small unsigned values (0,-1,1,-2 -> 0,1,2,3).
constexpr std::uint64_t ZigZag(std::int64_t value) {
  return (static_cast<std::uint64_t>(value) << 1) ^ static_cast<std::uint64_t>(value >> 63);
}
// The inverse of ZigZag.
constexpr std::int64_t UnZigZag(std::uint64_t value) {
  return static_cast<std::int64_t>(value >> 1) ^ -static_cast<std::int64_t>(value & 1U);
}

// Appends varints and strings to a byte string.
class ByteWriter {
 public:
  // Unsigned LEB128, 1 to 10 bytes.
  void PutVarint(std::uint64_t value);
  // Signed value as a zig-zag varint.
  void PutSigned(std::int64_t value) { PutVarint(ZigZag(value)); }
  // Length-prefixed bytes.
  void PutString(std::string_view text);
  // The bytes so far.
  const std::string& bytes() const { return bytes_; }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

// Reads what ByteWriter wrote; after the first error every read returns 0 / "" and failed() holds.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  std::uint64_t GetVarint();
  std::int64_t GetSigned() { return UnZigZag(GetVarint()); }
  std::string GetString();
  // A count of things each at least `min_bytes` long: fails if the rest cannot hold that many.
  std::uint64_t GetCount(std::size_t min_bytes);
  // Marks the input bad with a reason (the first reason is kept).
  void Fail(const std::string& why);
  bool failed() const { return !error_.empty(); }
  // The first error with the byte offset where it happened; empty if none.
  const std::string& error() const { return error_; }
  // Bytes not read yet.
  std::size_t remaining() const { return bytes_.size() - position_; }

 private:
  std::string_view bytes_;
  std::size_t position_ = 0;
  std::string error_;
};

}  // namespace pena::line_map
