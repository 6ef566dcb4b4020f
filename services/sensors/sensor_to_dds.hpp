#pragma once
// libpena sensor records -> the live sensor topics' types (idl/dds/sensors.idl), for publishers
// such as pena-sensor-replay. The reverse direction, with validation, is sensor_from_dds.hpp.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "pena/sensors/record.hpp"
#include "pena_dds/sensors.h"

namespace pena::services {

// One record as the sample of its topic; std::monostate for records no topic carries (ground
// truth). Throws std::length_error naming the field if the entity id or the beam count does not
// fit the IDL's bounds.
using SensorSample = std::variant<std::monostate, pena_dds::LaserScanSample, pena_dds::GyroSample,
                                  pena_dds::CompassSample, pena_dds::StrideSample,
                                  pena_dds::WheelOdometrySample>;
SensorSample ToDdsSensorSample(const sensors::SensorRecord& record, const std::string& entity_id,
                               std::uint64_t seq);

}  // namespace pena::services
