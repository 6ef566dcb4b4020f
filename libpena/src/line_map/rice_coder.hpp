#pragma once
// Adaptive Golomb-Rice codes on a bit stream, for the map packing (map_packing.hpp,
// docs/gateway.md "Map deltas"). A value u costs (u >> k) one-bits, a zero and k low bits, where each field's
// context picks k from the mean of the values it has coded so far (as in LOCO-I / JPEG-LS).
// Both sides update the context the same way, so nothing about k travels. Values whose quotient
// would exceed kRiceEscapeQuotient go as an escape: that many one-bits, 6 bits of bit length,
// then the value. The reader is bounds-checked like ByteReader: it fails once, with the bit
// offset, and returns zeros after.

#include <cstdint>
#include <string>
#include <string_view>

namespace pena::line_map {

inline constexpr std::uint64_t kRiceEscapeQuotient = 24;

// The running statistics of one field: k is the smallest with count << k >= sum.
class RiceContext {
 public:
  // `typical` is a prior: the value the first k is chosen for (e.g. 4096 for k = 12).
  explicit RiceContext(std::uint64_t typical) : sum_(typical > 0 ? typical : 1) {}
  int k() const;
  void Update(std::uint64_t value);

 private:
  std::uint64_t sum_;
  std::uint64_t count_ = 1;
};

// Appends bits, most significant first; the last byte is padded with zero bits.
class BitWriter {
 public:
  void PutBits(std::uint64_t value, int bits);  // the low `bits` of value, 0 <= bits <= 64
  void PutBit(bool bit) { PutBits(bit ? 1U : 0U, 1); }
  void PutRice(RiceContext& context, std::uint64_t value);
  // A string: its length with `length_context`, then 8 bits per byte.
  void PutText(RiceContext& length_context, std::string_view text);
  std::string Take();

 private:
  std::string bytes_;
  int used_bits_in_last_ = 8;  // bits of bytes_.back() already written
};

// Reads what BitWriter wrote.
class BitReader {
 public:
  explicit BitReader(std::string_view bytes) : bytes_(bytes) {}
  std::uint64_t GetBits(int bits);
  bool GetBit() { return GetBits(1) != 0U; }
  std::uint64_t GetRice(RiceContext& context);
  std::string GetText(RiceContext& length_context);
  // A count of things each at least `min_bits` long: fails if the rest cannot hold that many.
  std::uint64_t GetCount(RiceContext& context, std::uint64_t min_bits);
  void Fail(const std::string& why);
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  std::uint64_t remaining_bits() const { return 8 * bytes_.size() - position_bits_; }
  // Fails unless only zero padding (fewer than 8 bits) is left; returns !failed().
  bool Finish();

 private:
  std::string_view bytes_;
  std::uint64_t position_bits_ = 0;
  std::string error_;
};

}  // namespace pena::line_map
