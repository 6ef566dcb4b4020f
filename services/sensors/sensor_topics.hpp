#pragma once
// The live sensor topics (idl/dds/sensors.idl): names and the XML profiles of their writers and
// readers (deploy/dds/pena-qos.xml). Types, rates and QoS are listed in docs/dds.md.

#include "topics.hpp"

namespace pena::services::topics {

// pena_dds::LaserScanSample, keyed by entity, at the laser's rate.
inline constexpr TopicSpec kSensorScan{"pena/sensors/scan", "pena_sensor_scan_writer",
                                       "pena_sensor_scan_reader"};
// pena_dds::GyroSample (humans, 100 Hz in simulation).
inline constexpr TopicSpec kSensorGyro{"pena/sensors/gyro", "pena_sensor_fast_writer",
                                       "pena_sensor_fast_reader"};
// pena_dds::CompassSample (humans, 10 Hz).
inline constexpr TopicSpec kSensorCompass{"pena/sensors/compass", "pena_sensor_fast_writer",
                                          "pena_sensor_fast_reader"};
// pena_dds::StrideSample (humans, one per step).
inline constexpr TopicSpec kSensorStride{"pena/sensors/stride", "pena_sensor_fast_writer",
                                         "pena_sensor_fast_reader"};
// pena_dds::WheelOdometrySample (robots, 20 Hz).
inline constexpr TopicSpec kSensorWheelOdometry{"pena/sensors/wheel_odometry",
                                                "pena_sensor_fast_writer",
                                                "pena_sensor_fast_reader"};
// pena_dds::SensorStreamStatus: the start and end-of-stream markers.
inline constexpr TopicSpec kSensorStatus{"pena/sensors/status", "pena_sensor_status_writer",
                                         "pena_sensor_status_reader"};

}  // namespace pena::services::topics
