#pragma once
// Heading from a gyro and a compass fused by a Kalman filter (paper section 2.1).
// State: heading (rad, mission frame, CCW from +x) and gyro bias (rad/s).

#include <Eigen/Core>
#include <optional>

#include "pena/sensors/inertial.hpp"

namespace pena::dead_reckoning {

// Noise model and gating of the heading filter. Validated by HeadingFilter's constructor.
struct HeadingFilterOptions {
  double gyro_noise_rad_s = 0.01;            // white rate noise density, rad/s per sqrt(Hz)
  double bias_random_walk_rad_s2 = 2e-4;     // bias drift density, rad/s^2 per sqrt(Hz)
  double compass_noise_rad = 0.05;           // compass reading standard deviation
  // Compass readings whose normalised innovation squared exceeds this are rejected as magnetic
  // disturbances (chi-square, 1 dof: 9 = 3 sigma).
  double compass_gate_chi2 = 9.0;
  double max_gyro_gap_s = 0.5;               // longer gaps are not integrated (see Predict)
  double initial_heading_sigma_rad = 0.05;
  double initial_bias_sigma_rad_s = 0.02;
};

// Why the filter did not use a sample as is.
enum class HeadingEvent { kNone, kCompassRejected, kGyroGap, kOutOfOrder };

// Kalman filter on [heading, bias]. Gyro samples predict, compass samples correct.
class HeadingFilter {
 public:
  // Throws std::invalid_argument naming the field if an option is out of range.
  HeadingFilter(const HeadingFilterOptions& options, double initial_heading_rad, double stamp_s);

  // Integrates the bias-corrected rate since the last gyro stamp; a gap over max_gyro_gap_s only
  // grows the heading variance and returns kGyroGap.
  HeadingEvent Predict(const sensors::GyroSample& gyro);

  // Corrects heading and bias with a compass reading unless the innovation gate rejects it.
  HeadingEvent Update(const sensors::CompassSample& compass);

  // Replaces the heading after an external correction (scan matching, operator); keeps the bias.
  void Reset(double heading_rad, double heading_sigma_rad);

  double heading_rad() const { return state_(0); }
  double bias_rad_s() const { return state_(1); }
  double heading_sigma_rad() const;
  // Heading extrapolated to `stamp_s` with the last bias-corrected rate (for scans between gyro
  // samples).
  double HeadingAt(double stamp_s) const;
  double stamp_s() const { return stamp_s_; }

 private:
  HeadingFilterOptions options_;
  Eigen::Vector2d state_;
  Eigen::Matrix2d covariance_;
  double stamp_s_;
  double last_rate_rad_s_ = 0.0;
};

}  // namespace pena::dead_reckoning
