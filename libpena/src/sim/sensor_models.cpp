#include "pena/sim/sensor_models.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/sensors/laser_scan.hpp"

namespace pena::sim {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

double SmokeMaxRange(const std::vector<SmokeZone>& smoke, const Eigen::Vector2d& position_m,
                     double clear_max_range_m) {
  double range = clear_max_range_m;
  for (const SmokeZone& zone : smoke) {
    if (zone.area.Contains(position_m)) range = std::min(range, zone.max_range_m);
  }
  return range;
}

LaserNoiseModel::LaserNoiseModel(const LaserNoiseOptions& options, Random random)
    : options_(options), random_(random) {
  Require(options.range_noise_sd_m >= 0.0, "laser_noise.range_noise_sd_m must be >= 0 m");
  Require(options.dropout_probability >= 0.0 && options.dropout_probability <= 1.0,
          "laser_noise.dropout_probability must be in [0, 1]");
}

float LaserNoiseModel::Measure(const BeamHit& hit, double max_range_m) {
  // Draw both numbers for every beam so the stream position does not depend on the geometry:
  // moving one wall then changes only the beams that see it.
  const bool dropped = random_.Bernoulli(options_.dropout_probability);
  const double noise_m = random_.Normal(0.0, options_.range_noise_sd_m);
  if (hit.kind == HitKind::kNothing || dropped || hit.range_m > max_range_m) {
    return sensors::LaserScan::kNoReturn;
  }
  const double measured = std::clamp(hit.range_m + noise_m, 0.001, max_range_m);
  if (measured >= max_range_m) return sensors::LaserScan::kNoReturn;
  // Millimetre resolution, as a SICK LMS reports it.
  return static_cast<float>(std::round(measured * 1000.0) / 1000.0);
}

GyroModel::GyroModel(const GyroOptions& options, Random random)
    : options_(options), random_(random) {
  Require(options.noise_sd_rad_s >= 0.0, "gyro.noise_sd_rad_s must be >= 0 rad/s");
  Require(options.initial_bias_sd_rad_s >= 0.0, "gyro.initial_bias_sd_rad_s must be >= 0 rad/s");
  Require(options.bias_walk_rad_s_per_sqrt_s >= 0.0,
          "gyro.bias_walk_rad_s_per_sqrt_s must be >= 0 rad/s/sqrt(s)");
  bias_rad_s_ = random_.Normal(0.0, options.initial_bias_sd_rad_s);
}

sensors::GyroSample GyroModel::Measure(const TrueState& state, double dt_s) {
  bias_rad_s_ += options_.bias_walk_rad_s_per_sqrt_s * std::sqrt(dt_s) * random_.Normal();
  return {state.stamp_s,
          state.yaw_rate_rad_s + bias_rad_s_ + random_.Normal(0.0, options_.noise_sd_rad_s)};
}

CompassModel::CompassModel(const CompassOptions& options,
                           std::vector<MagneticDisturbance> disturbances, Random random)
    : options_(options), disturbances_(std::move(disturbances)), random_(random) {
  Require(options.noise_sd_rad >= 0.0, "compass.noise_sd_rad must be >= 0 rad");
  for (const MagneticDisturbance& disturbance : disturbances_) {
    Require(disturbance.radius_m > 0.0, "magnetic disturbance radius_m must be > 0 m");
  }
}

double CompassModel::DisturbanceAt(const Eigen::Vector2d& position_m) const {
  double offset_rad = 0.0;
  for (const MagneticDisturbance& disturbance : disturbances_) {
    const double distance_m = (position_m - disturbance.center_m).norm();
    offset_rad +=
        disturbance.peak_offset_rad * std::max(0.0, 1.0 - distance_m / disturbance.radius_m);
  }
  return offset_rad;
}

sensors::CompassSample CompassModel::Measure(const TrueState& state) {
  const Eigen::Vector2d position(state.world_from_body.x_m, state.world_from_body.y_m);
  const double heading = state.world_from_body.theta_rad + DisturbanceAt(position) +
                         random_.Normal(0.0, options_.noise_sd_rad);
  return {state.stamp_s, geometry::NormalizeAngle(heading)};
}

StrideModel::StrideModel(const StrideOptions& options, Random random)
    : options_(options), random_(random), landing_random_(random.Derive(1)) {
  Require(options.scale_error_sd >= 0.0, "stride.scale_error_sd must be >= 0");
  Require(options.max_scale_error >= 0.0 && options.max_scale_error < 1.0,
          "stride.max_scale_error must be in [0, 1)");
  Require(options.step_noise_sd >= 0.0, "stride.step_noise_sd must be >= 0");
  scale_error_ = std::clamp(random_.Normal(0.0, options.scale_error_sd), -options.max_scale_error,
                            options.max_scale_error);
}

sensors::StrideSample StrideModel::Measure(double stamp_s, double true_length_m) {
  const double factor = 1.0 + scale_error_ + random_.Normal(0.0, options_.step_noise_sd);
  return {stamp_s, std::max(0.0, true_length_m * factor)};
}

sensors::StrideSample StrideModel::MeasureLanding(double stamp_s, double true_length_m) {
  const double factor = 1.0 + scale_error_ + landing_random_.Normal(0.0, options_.step_noise_sd);
  return {stamp_s, std::max(0.0, true_length_m * factor)};
}

WheelOdometryModel::WheelOdometryModel(const WheelOdometryOptions& options, Random random)
    : options_(options), random_(random) {
  Require(options.distance_scale_sd >= 0.0 && options.yaw_scale_sd >= 0.0,
          "wheel_odometry.distance_scale_sd and yaw_scale_sd must be >= 0");
  Require(options.velocity_noise_sd_m_s >= 0.0,
          "wheel_odometry.velocity_noise_sd_m_s must be >= 0 m/s");
  Require(options.yaw_rate_noise_sd_rad_s >= 0.0,
          "wheel_odometry.yaw_rate_noise_sd_rad_s must be >= 0 rad/s");
  Require(options.slip_rate_per_s >= 0.0 && options.slip_duration_s >= 0.0,
          "wheel_odometry.slip_rate_per_s and slip_duration_s must be >= 0");
  distance_scale_ = 1.0 + std::clamp(random_.Normal(0.0, options.distance_scale_sd), -0.2, 0.2);
  yaw_scale_ = 1.0 + std::clamp(random_.Normal(0.0, options.yaw_scale_sd), -0.2, 0.2);
}

void WheelOdometryModel::Advance(const TrueState& state, double dt_s) {
  if (state.stamp_s >= slip_until_s_ && random_.Bernoulli(options_.slip_rate_per_s * dt_s) &&
      state.speed_m_s > 0.05) {
    slip_until_s_ = state.stamp_s + options_.slip_duration_s;
    slip_yaw_rate_rad_s_ = random_.Normal(0.0, options_.slip_yaw_rate_sd_rad_s);
  }
  const bool slipping = state.stamp_s < slip_until_s_;
  const double v = state.forward_velocity_m_s * distance_scale_ +
                   random_.Normal(0.0, options_.velocity_noise_sd_m_s);
  const double w = state.yaw_rate_rad_s * yaw_scale_ + (slipping ? slip_yaw_rate_rad_s_ : 0.0) +
                   random_.Normal(0.0, options_.yaw_rate_noise_sd_rad_s);
  // Midpoint integration, as a robot's odometry would do it.
  geometry::Pose2& pose = current_.odom_pose;
  const double mid = pose.theta_rad + 0.5 * w * dt_s;
  pose.x_m += v * dt_s * std::cos(mid);
  pose.y_m += v * dt_s * std::sin(mid);
  pose.theta_rad = geometry::NormalizeAngle(pose.theta_rad + w * dt_s);
  current_.stamp_s = state.stamp_s;
  current_.forward_velocity_m_s = v;
  current_.yaw_rate_rad_s = w;
}

}  // namespace pena::sim
