#pragma once
// Kalman-style gating of the fusion's virtual-scan corrections (paper section 4.2). The
// fusion keeps, per entity, the uncertainty of the entity's pose in the map frame: it grows with
// the distance the entity's own odometry travelled and shrinks at each accepted correction. A
// match (ComputeCorrection) becomes a measurement whose covariance comes from the matcher's
// information matrix J^T J; along a direction J^T J hardly constrains (a corridor's axis) the
// measurement says nothing, so the entity is never moved along it. The measurement is blended
// with the prediction (gain P (P + R)^-1) instead of replacing it, and an innovation beyond the
// Mahalanobis gate (an aliased junction, a wrong map) is refused.

#include <Eigen/Core>
#include <optional>
#include <vector>
#include <string>

#include "pena/fusion/correction.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"

namespace pena::fusion {

// Options of CorrectionFilter; validated by its constructor (messages name field and unit).
struct CorrectionFilterOptions {
  // Odometry drift: position variance grows by (this)^2 per metre travelled. m / sqrt(m).
  double translation_noise_m_per_sqrt_m = 0.08;
  // Heading variance grows by (this)^2 per metre travelled. rad / sqrt(m).
  double heading_noise_rad_per_sqrt_m = 0.006;
  // ... and by (this)^2 per radian turned. rad / sqrt(rad).
  double turn_noise_rad_per_sqrt_rad = 0.03;
  double initial_sd_m = 0.05;       // at the known start, metres
  double initial_sd_rad = 0.01;     // radians
  double max_sd_m = 5.0;            // the growth stops here, metres
  double max_sd_rad = 0.35;         // radians
  // Point-to-line residual of a good match: R = residual_sd_m^2 (J^T J)^-1. Metres.
  double residual_sd_m = 0.05;
  // Added to every measurement: the global map's own wall error. Metres, radians.
  double map_sd_m = 0.10;
  double map_sd_rad = 0.015;
  // A prediction with a position sd below this is not updated: the map's correlated errors would
  // only pull it towards themselves. Metres.
  double min_update_sd_m = 0.05;
  // Translation eigenvalue ratio (min / max) of J^T J below which the weak axis is dropped.
  double degenerate_eigen_ratio = 0.05;
  double gate_mahalanobis_sq = 16.3;  // innovation gate (chi^2, 3 dof: 99.9 %)
  double refused_growth = 1.5;  // a refused match multiplies the variances by this, >= 1
  // The match window covers +- this many standard deviations of the prediction ...
  double window_sigmas = 3.0;
  // ... but at least this (full extents), metres / radians, and at most the options' window.
  double min_window_m = 0.3;
  double min_window_rad = 0.07;
  // The noise above is a lower bound, scaled up online by covariance matching (Mehra 1972): once
  // this many matches have been compared, a median squared Mahalanobis distance of their
  // innovations above chi^2(3)'s median says the odometry drifts more than assumed, and the
  // process noise and the prediction are scaled by the ratio (down again, to 1, when it is
  // below). 0 = off. A median of several matches: one aliased match or one wrong wall does not.
  int adapt_window = 8;
  double max_noise_scale = 400.0;  // the variance scale's cap (20x the standard deviations), >= 1
};

// Throws std::invalid_argument naming the field and unit.
void ValidateCorrectionFilterOptions(const CorrectionFilterOptions& options);

// The outcome of CorrectionFilter::Update.
struct FilteredCorrection {
  bool accepted = false;
  geometry::Pose2 map_from_body;  // blended pose (the prediction when not accepted), map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // after the update (x, y, theta)
  double mahalanobis_sq = 0.0;    // of the innovation
  double constraint_ratio = 0.0;  // min / max translation eigenvalue of the match's J^T J
  bool degenerate = false;        // the weak axis was dropped
  std::string reason;             // why not accepted
};

// One entity's pose uncertainty and the blending of corrections into it. Not thread-safe.
class CorrectionFilter {
 public:
  explicit CorrectionFilter(const CorrectionFilterOptions& options);

  // Grows the uncertainty by the odometry's motion since the previous call (odom frame): by the
  // options' noise model, or by the growth of `reported_covariance` (the entity's own estimate
  // of its pose's covariance, x_m, y_m, theta_rad) since the previous call where that is larger.
  void Predict(const geometry::Pose2& odom_from_body,
               const std::optional<Eigen::Matrix3d>& reported_covariance = std::nullopt);
  // The match window for the next correction: +- window_sigmas of the prediction, clamped
  // between the minimum and `max_window` (steps kept from max_window).
  scan_matching::SearchWindow Window(const scan_matching::SearchWindow& max_window) const;
  // Blends an accepted match (ComputeCorrection's result for the pose `predicted`, map frame)
  // into the prediction. A refused match grows the uncertainty by refused_growth (except when
  // the prediction is already more precise than the map).
  FilteredCorrection Update(const geometry::Pose2& predicted, const FusionCorrection& match);

  // Current covariance of the entity's pose in the map frame (x_m, y_m, theta_rad).
  const Eigen::Matrix3d& covariance() const { return covariance_; }
  // The process noise's variance scale estimated so far (1: the options' figures).
  double noise_scale() const { return noise_scale_; }

 private:
  // Multiplies the covariance (capped at max_sd_m / max_sd_rad).
  void Grow(double factor);
  // Covariance matching: records a match's squared Mahalanobis distance and rescales the noise
  // once adapt_window of them are in.
  void Adapt(double mahalanobis_sq);

  CorrectionFilterOptions options_;
  Eigen::Matrix3d covariance_;
  std::optional<geometry::Pose2> last_odom_;
  std::optional<Eigen::Matrix3d> last_reported_;
  double noise_scale_ = 1.0;
  std::vector<double> recent_mahalanobis_sq_;
};

}  // namespace pena::fusion
