#pragma once
// One timestamped item of a sensor stream, whatever its sensor.

#include <variant>

#include "pena/sensors/ground_truth.hpp"
#include "pena/sensors/inertial.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/sensors/wheel_odometry.hpp"

namespace pena::sensors {

using SensorRecord =
    std::variant<LaserScan, GyroSample, CompassSample, StrideSample, WheelOdometry, GroundTruth>;

// The record's timestamp, seconds.
double StampOf(const SensorRecord& record);

}  // namespace pena::sensors
