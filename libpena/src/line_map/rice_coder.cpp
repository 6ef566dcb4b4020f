#include "rice_coder.hpp"

#include <algorithm>
#include <bit>

namespace pena::line_map {
namespace {

// The running sum is capped so it never overflows; k then tops out at 48.
constexpr std::uint64_t kMaxSum = std::uint64_t{1} << 48;
// After this many values the statistics are halved, so k follows slow changes.
constexpr std::uint64_t kHalvingCount = 64;
constexpr int kLengthBits = 6;  // an escaped value's bit length minus one

}  // namespace

int RiceContext::k() const {
  int k = 0;
  while ((count_ << k) < sum_) ++k;
  return k;
}

void RiceContext::Update(std::uint64_t value) {
  sum_ = std::min(kMaxSum, sum_ + std::min(value, kMaxSum));
  if (++count_ >= kHalvingCount) {
    sum_ = std::max<std::uint64_t>(1, sum_ / 2);
    count_ /= 2;
  }
}

void BitWriter::PutBits(std::uint64_t value, int bits) {
  for (int i = bits - 1; i >= 0; --i) {
    if (used_bits_in_last_ == 8) {
      bytes_.push_back('\0');
      used_bits_in_last_ = 0;
    }
    if (((value >> i) & 1U) != 0U) {
      bytes_.back() = static_cast<char>(static_cast<unsigned char>(bytes_.back()) |
                                        (0x80U >> used_bits_in_last_));
    }
    ++used_bits_in_last_;
  }
}

void BitWriter::PutRice(RiceContext& context, std::uint64_t value) {
  const int k = context.k();
  const std::uint64_t quotient = value >> k;
  if (quotient < kRiceEscapeQuotient) {
    for (std::uint64_t i = 0; i < quotient; ++i) PutBit(true);
    PutBit(false);
    PutBits(value, k);
  } else {
    for (std::uint64_t i = 0; i < kRiceEscapeQuotient; ++i) PutBit(true);
    const int length = std::max(1, static_cast<int>(std::bit_width(value)));
    PutBits(static_cast<std::uint64_t>(length - 1), kLengthBits);
    PutBits(value, length);
  }
  context.Update(value);
}

void BitWriter::PutText(RiceContext& length_context, std::string_view text) {
  PutRice(length_context, text.size());
  for (char c : text) PutBits(static_cast<unsigned char>(c), 8);
}

std::string BitWriter::Take() {
  used_bits_in_last_ = 8;
  return std::move(bytes_);
}

std::uint64_t BitReader::GetBits(int bits) {
  if (failed()) return 0;
  if (static_cast<std::uint64_t>(bits) > remaining_bits()) {
    Fail("truncated: " + std::to_string(bits) + " bits wanted, " +
         std::to_string(remaining_bits()) + " left");
    return 0;
  }
  std::uint64_t value = 0;
  for (int i = 0; i < bits; ++i) {
    const auto byte = static_cast<unsigned char>(bytes_[position_bits_ / 8]);
    value = (value << 1) | ((byte >> (7 - position_bits_ % 8)) & 1U);
    ++position_bits_;
  }
  return value;
}

std::uint64_t BitReader::GetRice(RiceContext& context) {
  const int k = context.k();
  std::uint64_t quotient = 0;
  while (!failed() && quotient < kRiceEscapeQuotient && GetBit()) ++quotient;
  if (failed()) return 0;
  std::uint64_t value = 0;
  if (quotient < kRiceEscapeQuotient) {
    if (k < 64 && quotient > (~std::uint64_t{0} >> k)) {
      Fail("Rice value overflows");
      return 0;
    }
    value = (quotient << k) | GetBits(k);
  } else {
    const int length = static_cast<int>(GetBits(kLengthBits)) + 1;
    value = GetBits(length);
  }
  if (failed()) return 0;
  context.Update(value);
  return value;
}

std::string BitReader::GetText(RiceContext& length_context) {
  const std::uint64_t size = GetRice(length_context);
  if (failed()) return {};
  if (size > remaining_bits() / 8) {
    Fail("string of " + std::to_string(size) + " bytes past the end");
    return {};
  }
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  for (std::uint64_t i = 0; i < size; ++i) text.push_back(static_cast<char>(GetBits(8)));
  return text;
}

std::uint64_t BitReader::GetCount(RiceContext& context, std::uint64_t min_bits) {
  const std::uint64_t count = GetRice(context);
  if (failed()) return 0;
  if (min_bits > 0 && count > remaining_bits() / min_bits) {
    Fail("count " + std::to_string(count) + " exceeds the " + std::to_string(remaining_bits()) +
         " bits left");
    return 0;
  }
  return count;
}

void BitReader::Fail(const std::string& why) {
  if (error_.empty()) {
    error_ = "byte " + std::to_string(position_bits_ / 8) + " bit " +
             std::to_string(position_bits_ % 8) + ": " + why;
  }
}

bool BitReader::Finish() {
  if (!failed()) {
    const std::uint64_t left = remaining_bits();
    if (left >= 8) {
      Fail(std::to_string(left / 8) + " trailing bytes");
    } else if (GetBits(static_cast<int>(left)) != 0U) {
      Fail("non-zero padding");
    }
  }
  return !failed();
}

}  // namespace pena::line_map
