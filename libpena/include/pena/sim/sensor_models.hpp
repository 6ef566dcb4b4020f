#pragma once
// Error models of the simulated sensors: laser noise, drop-outs and smoke; gyro noise with a
// drifting bias; compass noise with magnetic disturbances; stride length error; wheel odometry
// with scale errors and slip. Each model owns its random stream, so one sensor's draws never
// shift another's.

#include <Eigen/Core>
#include <vector>

#include "pena/sensors/inertial.hpp"
#include "pena/sensors/wheel_odometry.hpp"
#include "pena/sim/laser_raycaster.hpp"
#include "pena/sim/random.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/true_motion.hpp"

namespace pena::sim {

// Laser range errors (SICK LMS-like).
struct LaserNoiseOptions {
  double range_noise_sd_m = 0.01;     // Gaussian range noise
  double dropout_probability = 0.01;  // a beam returns nothing
};

// The laser's maximum range at `position_m`: the smallest smoke-zone range among zones holding
// the laser, else `clear_max_range_m`.
double SmokeMaxRange(const std::vector<SmokeZone>& smoke, const Eigen::Vector2d& position_m,
                     double clear_max_range_m);

// Turns true beam hits into measured ranges.
class LaserNoiseModel {
 public:
  // Throws std::invalid_argument naming a bad option.
  LaserNoiseModel(const LaserNoiseOptions& options, Random random);
  // Measured range in metres, or sensors::LaserScan::kNoReturn for no hit, a hit beyond
  // `max_range_m` (smoke) or a drop-out.
  float Measure(const BeamHit& hit, double max_range_m);

 private:
  LaserNoiseOptions options_;
  Random random_;
};

// Gyro errors (MEMS rate gyro).
struct GyroOptions {
  double noise_sd_rad_s = 0.005;               // white noise per sample (~0.3 deg/s)
  double initial_bias_sd_rad_s = 0.005;        // bias at switch-on
  double bias_walk_rad_s_per_sqrt_s = 0.0005;  // bias random walk
};

// A yaw-rate gyro: true mean rate over the sample interval + bias + noise.
class GyroModel {
 public:
  GyroModel(const GyroOptions& options, Random random);
  // The reading for `state` after `dt_s` since the last reading (the bias walks over dt_s).
  sensors::GyroSample Measure(const TrueState& state, double dt_s);
  double bias_rad_s() const { return bias_rad_s_; }

 private:
  GyroOptions options_;
  Random random_;
  double bias_rad_s_;
};

// Compass errors.
struct CompassOptions {
  double noise_sd_rad = 0.035;  // ~2 deg
};

// A magnetic compass giving heading in the mission frame, offset near steel structures.
class CompassModel {
 public:
  CompassModel(const CompassOptions& options, std::vector<MagneticDisturbance> disturbances,
               Random random);
  // Sum of the disturbance offsets at `position_m`, radians.
  double DisturbanceAt(const Eigen::Vector2d& position_m) const;
  sensors::CompassSample Measure(const TrueState& state);

 private:
  CompassOptions options_;
  std::vector<MagneticDisturbance> disturbances_;
  Random random_;
};

// Stride sensor (SiLMU) errors: a per-mission scale error plus per-step noise, about 5 %.
struct StrideOptions {
  double scale_error_sd = 0.03;   // drawn once per entity
  double max_scale_error = 0.06;  // clamp of that draw
  double step_noise_sd = 0.05;    // relative noise of each step
};

// Measures step lengths.
class StrideModel {
 public:
  StrideModel(const StrideOptions& options, Random random);
  sensors::StrideSample Measure(double stamp_s, double true_length_m);
  // The last, partial step of a walker coming to a stand: the trailing foot lands. Its noise has
  // a stream of its own, so the steps of the walk keep the noise they had without it.
  sensors::StrideSample MeasureLanding(double stamp_s, double true_length_m);
  double scale_error() const { return scale_error_; }

 private:
  StrideOptions options_;
  Random random_;
  Random landing_random_;
  double scale_error_;
};

// Wheel odometry errors of a robot.
struct WheelOdometryOptions {
  double distance_scale_sd = 0.02;        // per-robot scale error of travelled distance
  double yaw_scale_sd = 0.02;             // per-robot scale error of rotation
  double velocity_noise_sd_m_s = 0.01;    // per sample
  double yaw_rate_noise_sd_rad_s = 0.01;  // per sample
  double slip_rate_per_s = 1.0 / 30.0;    // wheel slip events
  double slip_duration_s = 0.5;
  double slip_yaw_rate_sd_rad_s = 0.15;  // spurious rotation while slipping
};

// Integrates measured wheel velocities into an odometry pose (odom frame = the start pose at the
// origin).
class WheelOdometryModel {
 public:
  WheelOdometryModel(const WheelOdometryOptions& options, Random random);
  // Integrates the interval of `dt_s` ending at `state` (call for every motion sample).
  void Advance(const TrueState& state, double dt_s);
  // The current integrated reading.
  sensors::WheelOdometry Current() const { return current_; }

 private:
  WheelOdometryOptions options_;
  Random random_;
  double distance_scale_;
  double yaw_scale_;
  double slip_until_s_ = -1.0;
  double slip_yaw_rate_rad_s_ = 0.0;
  sensors::WheelOdometry current_;
};

}  // namespace pena::sim
