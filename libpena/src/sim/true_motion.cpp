#include "pena/sim/true_motion.hpp"

namespace pena::sim {

std::vector<Waypoint> UnrollRoute(const EntitySpec& spec) {
  std::vector<Waypoint> unrolled;
  for (int lap = 0; lap < spec.laps; ++lap) {
    unrolled.insert(unrolled.end(), spec.route.begin(), spec.route.end());
  }
  return unrolled;
}

double SampleStamp(double start_time_s, std::size_t index, double rate_hz) {
  // Dividing the integer index (rather than accumulating dt) gives the nearest double to the exact
  // stamp, so 25 / 100.0 is exactly 0.25 and scan stamps print back unchanged.
  return start_time_s + static_cast<double>(index) / rate_hz;
}

}  // namespace pena::sim
