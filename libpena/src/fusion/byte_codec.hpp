#pragma once
// Little-endian fixed-width fields, doubles by their bits, strings with a u32 length: the bricks
// of fusion_codec.cpp. Internal to the fusion module.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pena::fusion::detail {

// Appends fields to a byte string.
class ByteWriter {
 public:
  void U8(std::uint8_t value) { bytes_.push_back(static_cast<char>(value)); }
  void U64(std::uint64_t value) {
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
  }
  void I64(std::int64_t value) { U64(static_cast<std::uint64_t>(value)); }
  void F64(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    U64(bits);
  }
  void Text(std::string_view text) {
    U64(text.size());
    bytes_.append(text);
  }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

// A malformed buffer; `offset` is where reading failed.
class ByteError : public std::runtime_error {
 public:
  ByteError(const std::string& what, std::size_t offset)
      : std::runtime_error(what), offset_(offset) {}
  std::size_t offset() const { return offset_; }

 private:
  std::size_t offset_;
};

// Reads fields back; throws ByteError past the end.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  std::uint8_t U8() {
    Need(1, "u8");
    return static_cast<std::uint8_t>(bytes_[offset_++]);
  }
  std::uint64_t U64() {
    Need(8, "u64");
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) {
      value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[offset_ + i])) << (8 * i);
    }
    offset_ += 8;
    return value;
  }
  std::int64_t I64() { return static_cast<std::int64_t>(U64()); }
  double F64() {
    const std::uint64_t bits = U64();
    double value = 0.0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  std::string Text() {
    const std::uint64_t size = U64();
    Need(size, "string of " + std::to_string(size) + " bytes");
    std::string text(bytes_.substr(offset_, size));
    offset_ += size;
    return text;
  }
  // A count of items each at least min_bytes long (guards a corrupt count).
  std::size_t Count(std::size_t min_bytes) {
    const std::uint64_t count = U64();
    if (count > (bytes_.size() - offset_) / std::max<std::size_t>(1, min_bytes)) {
      throw ByteError("count " + std::to_string(count) + " exceeds the remaining bytes", offset_);
    }
    return static_cast<std::size_t>(count);
  }
  [[noreturn]] void Fail(const std::string& what) const { throw ByteError(what, offset_); }
  bool done() const { return offset_ == bytes_.size(); }
  std::size_t offset() const { return offset_; }
  // The codec version the bytes were written with (fields added later are absent before it).
  std::uint8_t version() const { return version_; }
  void set_version(std::uint8_t version) { version_ = version; }

 private:
  void Need(std::uint64_t size, const std::string& what) const {
    if (size > bytes_.size() - offset_) {
      throw ByteError("truncated: " + what + " needs " + std::to_string(size) + " bytes, " +
                          std::to_string(bytes_.size() - offset_) + " left",
                      offset_);
    }
  }
  std::uint8_t version_ = 0;
  std::string_view bytes_;
  std::size_t offset_ = 0;
};

}  // namespace pena::fusion::detail
