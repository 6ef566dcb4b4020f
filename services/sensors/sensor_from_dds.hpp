#pragma once
// The live sensor topics' types (idl/dds/sensors.idl) -> libpena records, validated: the samples
// come from any publisher on the domain, so nothing in them is trusted. A refused sample is
// data (SensorCheck::error), never an exception.

#include <cstddef>
#include <optional>
#include <string>

#include "pena/sensors/record.hpp"
#include "pena_dds/sensors.h"

namespace pena::services {

// The record a sample gives, or why it gives none.
struct SensorCheck {
  std::optional<sensors::SensorRecord> record;  // nullopt: refused
  std::string error;                            // why it was refused (names the field)
  std::size_t bad_ranges = 0;                   // NaN or negative ranges made no-returns
};

// Scans: every value finite, max_range_m > 0, angle_increment_rad != 0, 1..max_beams beams
// (max_beams at most SCAN_MAX_BEAMS). NaN and negative ranges become no-returns (counted);
// +inf stays the no-return it is.
SensorCheck FromDds(const pena_dds::LaserScanSample& sample,
                    std::size_t max_beams = pena_dds::SCAN_MAX_BEAMS);
// Gyro, compass, wheel odometry: every value finite. Stride: length finite and >= 0.
SensorCheck FromDds(const pena_dds::GyroSample& sample);
SensorCheck FromDds(const pena_dds::CompassSample& sample);
SensorCheck FromDds(const pena_dds::StrideSample& sample);
SensorCheck FromDds(const pena_dds::WheelOdometrySample& sample);

}  // namespace pena::services
