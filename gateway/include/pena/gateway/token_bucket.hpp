#pragma once
// A token bucket in bits: the link's bit budget. Tokens refill at rate_bit_s up to capacity_bits;
// a send may overdraw (one oversized frame), and the debt is repaid before the next send.

namespace pena::gateway {

class TokenBucket {
 public:
  // Starts full. Throws std::invalid_argument unless rate_bit_s > 0 and capacity_bits > 0.
  TokenBucket(double rate_bit_s, double capacity_bits);
  // Adds the tokens earned since the last call (time must not go backwards; it is clamped).
  void Refill(double now_s);
  // Removes `bits` (may go negative).
  void Consume(double bits) { tokens_bits_ -= bits; }
  // Tokens now, in bits (negative while in debt).
  double tokens_bits() const { return tokens_bits_; }
  // True if the bucket holds its whole capacity.
  bool full() const { return tokens_bits_ >= capacity_bits_; }
  double rate_bit_s() const { return rate_bit_s_; }
  double capacity_bits() const { return capacity_bits_; }

 private:
  double rate_bit_s_;
  double capacity_bits_;
  double tokens_bits_;
  double last_s_ = 0.0;
  bool started_ = false;
};

}  // namespace pena::gateway
