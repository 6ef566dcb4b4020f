#include "pena/sensors/record.hpp"

namespace pena::sensors {

double StampOf(const SensorRecord& record) {
  return std::visit([](const auto& item) { return item.stamp_s; }, record);
}

}  // namespace pena::sensors
