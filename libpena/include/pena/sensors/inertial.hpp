#pragma once
// Body-worn sensors of human dead reckoning (paper section 2.1): gyro, compass, stride length.

namespace pena::sensors {

// Yaw rate about the vertical axis from the gyro, rad/s, CCW positive; raw (bias included).
struct GyroSample {
  double stamp_s = 0.0;
  double yaw_rate_rad_s = 0.0;
};

// Heading from the compass in the mission frame, rad, CCW from +x; raw (disturbances included).
struct CompassSample {
  double stamp_s = 0.0;
  double heading_rad = 0.0;
};

// One step measured by the ultrasonic Stride Length Measurement Unit (SiLMU): the distance the
// body moved during the step ending at stamp_s, metres. The sensor gives length, not direction.
struct StrideSample {
  double stamp_s = 0.0;
  double length_m = 0.0;
};

}  // namespace pena::sensors
