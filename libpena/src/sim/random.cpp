#include "pena/sim/random.hpp"

#include <cmath>
#include <numbers>

namespace pena::sim {
namespace {

// SplitMix64 (Steele et al. 2014): spreads nearby seeds and salts over the whole state space, so
// streams for entity 0 and entity 1 are unrelated.
std::uint64_t SplitMix64(std::uint64_t value) {
  value += 0x9E3779B97F4A7C15ULL;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ULL;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBULL;
  return value ^ (value >> 31);
}

}  // namespace

Random::Random(std::uint64_t seed) : seed_(seed), engine_(SplitMix64(seed)) {}

Random Random::Derive(std::uint64_t salt) const {
  return Random(SplitMix64(seed_ ^ SplitMix64(salt + 0x632BE59BD9B4E019ULL)));
}

double Random::Uniform() {
  // The top 53 bits as a fraction: exact, and identical wherever mt19937_64 is.
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double Random::Uniform(double low, double high) { return low + (high - low) * Uniform(); }

double Random::Normal(double mean, double stddev) {
  if (has_cached_normal_) {
    has_cached_normal_ = false;
    return mean + stddev * cached_normal_;
  }
  // 1 - Uniform() lies in (0, 1], so the logarithm is finite.
  const double radius = std::sqrt(-2.0 * std::log(1.0 - Uniform()));
  const double angle = 2.0 * std::numbers::pi * Uniform();
  cached_normal_ = radius * std::sin(angle);
  has_cached_normal_ = true;
  return mean + stddev * radius * std::cos(angle);
}

bool Random::Bernoulli(double probability) { return Uniform() < probability; }

}  // namespace pena::sim
