#pragma once
// A seeded random source whose output is the same on every platform and standard library:
// mt19937_64 bits (specified exactly by the standard) with our own uniform and normal transforms
// (std::uniform_real_distribution and std::normal_distribution are implementation-defined).

#include <cstdint>
#include <random>

namespace pena::sim {

// Deterministic random numbers for the simulator. Copyable; copies continue the same sequence.
class Random {
 public:
  explicit Random(std::uint64_t seed);

  // An independent stream for a named purpose (entity index, sensor): same seed and salt give the
  // same stream, whatever else was drawn from this one.
  Random Derive(std::uint64_t salt) const;

  // Uniform in [0, 1) with 53 random bits.
  double Uniform();
  // Uniform in [low, high).
  double Uniform(double low, double high);
  // Normal with the given mean and standard deviation (Box-Muller, cached second value).
  double Normal(double mean = 0.0, double stddev = 1.0);
  // True with probability `probability`.
  bool Bernoulli(double probability);

 private:
  std::uint64_t seed_;
  std::mt19937_64 engine_;
  double cached_normal_ = 0.0;
  bool has_cached_normal_ = false;
};

}  // namespace pena::sim
