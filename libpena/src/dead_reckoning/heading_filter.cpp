#include "pena/dead_reckoning/heading_filter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"
#include "pena/geometry/pose2.hpp"

namespace pena::dead_reckoning {
namespace {

void RequirePositive(double value, const char* field, const char* unit) {
  RequireOption(value > 0.0 && std::isfinite(value), "heading_filter", field,
                std::string("> 0 ") + unit, value);
}

// A person can turn at up to ~200 deg/s: over an unobserved gyro gap the heading may change by
// that much, so the variance grows by (3.5 rad/s * gap)^2 rather than trusting a stale rate.
constexpr double kMaxTurnRateRadS = 3.5;

}  // namespace

HeadingFilter::HeadingFilter(const HeadingFilterOptions& options, double initial_heading_rad,
                             double stamp_s)
    : options_(options), stamp_s_(stamp_s) {
  RequirePositive(options.gyro_noise_rad_s, "gyro_noise_rad_s", "rad/s/sqrt(Hz)");
  RequirePositive(options.bias_random_walk_rad_s2, "bias_random_walk_rad_s2", "rad/s^2/sqrt(Hz)");
  RequirePositive(options.compass_noise_rad, "compass_noise_rad", "rad");
  RequirePositive(options.compass_gate_chi2, "compass_gate_chi2", "(chi-square)");
  RequirePositive(options.max_gyro_gap_s, "max_gyro_gap_s", "s");
  RequirePositive(options.initial_heading_sigma_rad, "initial_heading_sigma_rad", "rad");
  RequirePositive(options.initial_bias_sigma_rad_s, "initial_bias_sigma_rad_s", "rad/s");
  if (!std::isfinite(initial_heading_rad) || !std::isfinite(stamp_s)) {
    throw std::invalid_argument("heading_filter: initial heading and stamp must be finite");
  }
  state_ << geometry::NormalizeAngle(initial_heading_rad), 0.0;
  covariance_.setZero();
  covariance_(0, 0) = std::pow(options.initial_heading_sigma_rad, 2);
  covariance_(1, 1) = std::pow(options.initial_bias_sigma_rad_s, 2);
}

HeadingEvent HeadingFilter::Predict(const sensors::GyroSample& gyro) {
  const double dt = gyro.stamp_s - stamp_s_;
  if (!(dt >= 0.0) || !std::isfinite(gyro.yaw_rate_rad_s)) return HeadingEvent::kOutOfOrder;
  stamp_s_ = gyro.stamp_s;
  if (dt > options_.max_gyro_gap_s) {
    covariance_(0, 0) += std::pow(kMaxTurnRateRadS * dt, 2);
    last_rate_rad_s_ = 0.0;
    return HeadingEvent::kGyroGap;
  }
  // Rectangular integration of the bias-corrected rate; F = [1 -dt; 0 1].
  last_rate_rad_s_ = gyro.yaw_rate_rad_s - state_(1);
  state_(0) = geometry::NormalizeAngle(state_(0) + last_rate_rad_s_ * dt);
  Eigen::Matrix2d transition;
  transition << 1.0, -dt, 0.0, 1.0;
  Eigen::Matrix2d process_noise = Eigen::Matrix2d::Zero();
  process_noise(0, 0) = std::pow(options_.gyro_noise_rad_s, 2) * dt;
  process_noise(1, 1) = std::pow(options_.bias_random_walk_rad_s2, 2) * dt;
  covariance_ = transition * covariance_ * transition.transpose() + process_noise;
  return HeadingEvent::kNone;
}

HeadingEvent HeadingFilter::Update(const sensors::CompassSample& compass) {
  if (!std::isfinite(compass.heading_rad)) return HeadingEvent::kCompassRejected;
  // Innovation on the circle; H = [1 0].
  const double innovation = geometry::NormalizeAngle(compass.heading_rad - state_(0));
  const double innovation_variance = covariance_(0, 0) + std::pow(options_.compass_noise_rad, 2);
  // Innovation gating: near steel structures the compass is off by tens of degrees while the
  // gyro-propagated heading is still good, so a reading far outside its predicted spread is
  // rejected instead of bending the heading towards it.
  if (innovation * innovation / innovation_variance > options_.compass_gate_chi2) {
    return HeadingEvent::kCompassRejected;
  }
  const Eigen::Vector2d gain = covariance_.col(0) / innovation_variance;
  state_ += gain * innovation;
  state_(0) = geometry::NormalizeAngle(state_(0));
  const Eigen::Matrix2d joseph = Eigen::Matrix2d::Identity() - gain * Eigen::RowVector2d(1.0, 0.0);
  covariance_ = joseph * covariance_ * joseph.transpose() +
                gain * gain.transpose() * std::pow(options_.compass_noise_rad, 2);
  return HeadingEvent::kNone;
}

void HeadingFilter::Reset(double heading_rad, double heading_sigma_rad) {
  state_(0) = geometry::NormalizeAngle(heading_rad);
  // The correction is independent of the bias estimate: drop the cross-covariance.
  covariance_(0, 1) = covariance_(1, 0) = 0.0;
  covariance_(0, 0) = heading_sigma_rad * heading_sigma_rad;
}

double HeadingFilter::heading_sigma_rad() const { return std::sqrt(covariance_(0, 0)); }

double HeadingFilter::HeadingAt(double stamp_s) const {
  const double dt = std::clamp(stamp_s - stamp_s_, 0.0, options_.max_gyro_gap_s);
  return geometry::NormalizeAngle(state_(0) + last_rate_rad_s_ * dt);
}

}  // namespace pena::dead_reckoning
