#include "pena/gateway/token_bucket.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pena::gateway {

TokenBucket::TokenBucket(double rate_bit_s, double capacity_bits)
    : rate_bit_s_(rate_bit_s), capacity_bits_(capacity_bits), tokens_bits_(capacity_bits) {
  if (!(rate_bit_s > 0.0)) {
    throw std::invalid_argument("link.budget_bit_s must be > 0 bit/s, got " +
                                std::to_string(rate_bit_s));
  }
  if (!(capacity_bits > 0.0)) {
    throw std::invalid_argument("link.burst_bits must be > 0 bits, got " +
                                std::to_string(capacity_bits));
  }
}

void TokenBucket::Refill(double now_s) {
  if (started_ && now_s > last_s_) {
    tokens_bits_ = std::min(capacity_bits_, tokens_bits_ + (now_s - last_s_) * rate_bit_s_);
  }
  if (!started_ || now_s > last_s_) last_s_ = now_s;
  started_ = true;
}

}  // namespace pena::gateway
