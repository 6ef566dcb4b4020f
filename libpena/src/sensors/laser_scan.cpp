#include "pena/sensors/laser_scan.hpp"

namespace pena::sensors {

std::size_t LaserScan::CountReturns() const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < ranges_m.size(); ++i) count += IsReturn(i) ? 1 : 0;
  return count;
}

}  // namespace pena::sensors
