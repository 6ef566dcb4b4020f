#include "pena/fusion/correction_filter.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "fusion_checks.hpp"

namespace pena::fusion {
namespace {

// A variance standing for "no information" along a degenerate axis, m^2.
constexpr double kUnconstrainedVariance_m2 = 1e6;
// The median of chi^2 with 3 degrees of freedom: what the median squared Mahalanobis distance of
// innovations is when the filter's covariances are right.
constexpr double kChi2Median3 = 2.366;

// Rotates the (x, y) part of a covariance by `theta_rad` (body frame -> map frame).
Eigen::Matrix3d Rotate(const Eigen::Matrix3d& covariance, double theta_rad) {
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
  jacobian.topLeftCorner<2, 2>() << std::cos(theta_rad), -std::sin(theta_rad),
      std::sin(theta_rad), std::cos(theta_rad);
  return jacobian * covariance * jacobian.transpose();
}

}  // namespace

void ValidateCorrectionFilterOptions(const CorrectionFilterOptions& o) {
  using detail::Require;
  Require(o.translation_noise_m_per_sqrt_m >= 0.0,
          "correction_filter.translation_noise_m_per_sqrt_m must be >= 0 (m/sqrt(m))",
          o.translation_noise_m_per_sqrt_m);
  Require(o.heading_noise_rad_per_sqrt_m >= 0.0,
          "correction_filter.heading_noise_rad_per_sqrt_m must be >= 0 (rad/sqrt(m))",
          o.heading_noise_rad_per_sqrt_m);
  Require(o.turn_noise_rad_per_sqrt_rad >= 0.0,
          "correction_filter.turn_noise_rad_per_sqrt_rad must be >= 0 (rad/sqrt(rad))",
          o.turn_noise_rad_per_sqrt_rad);
  Require(o.initial_sd_m > 0.0, "correction_filter.initial_sd_m must be > 0 (metres)", o.initial_sd_m);
  Require(o.initial_sd_rad > 0.0, "correction_filter.initial_sd_rad must be > 0 (radians)",
          o.initial_sd_rad);
  Require(o.max_sd_m >= o.initial_sd_m, "correction_filter.max_sd_m must be >= initial_sd_m (metres)",
          o.max_sd_m);
  Require(o.max_sd_rad >= o.initial_sd_rad,
          "correction_filter.max_sd_rad must be >= initial_sd_rad (radians)", o.max_sd_rad);
  Require(o.residual_sd_m > 0.0, "correction_filter.residual_sd_m must be > 0 (metres)",
          o.residual_sd_m);
  Require(o.min_update_sd_m >= 0.0, "correction_filter.min_update_sd_m must be >= 0 (metres)",
          o.min_update_sd_m);
  Require(o.map_sd_m > 0.0, "correction_filter.map_sd_m must be > 0 (metres)", o.map_sd_m);
  Require(o.map_sd_rad > 0.0, "correction_filter.map_sd_rad must be > 0 (radians)", o.map_sd_rad);
  Require(o.degenerate_eigen_ratio >= 0.0 && o.degenerate_eigen_ratio < 1.0,
          "correction_filter.degenerate_eigen_ratio must be in [0, 1)", o.degenerate_eigen_ratio);
  Require(o.gate_mahalanobis_sq > 0.0, "correction_filter.gate_mahalanobis_sq must be > 0",
          o.gate_mahalanobis_sq);
  Require(o.refused_growth >= 1.0, "correction_filter.refused_growth must be >= 1",
          o.refused_growth);
  Require(o.window_sigmas > 0.0, "correction_filter.window_sigmas must be > 0", o.window_sigmas);
  Require(o.min_window_m > 0.0, "correction_filter.min_window_m must be > 0 (metres)",
          o.min_window_m);
  Require(o.min_window_rad > 0.0, "correction_filter.min_window_rad must be > 0 (radians)",
          o.min_window_rad);
  Require(o.adapt_window >= 0, "correction_filter.adapt_window must be >= 0 (matches)",
          o.adapt_window);
  Require(o.max_noise_scale >= 1.0, "correction_filter.max_noise_scale must be >= 1",
          o.max_noise_scale);
}

CorrectionFilter::CorrectionFilter(const CorrectionFilterOptions& options) : options_(options) {
  ValidateCorrectionFilterOptions(options_);
  covariance_ = Eigen::Vector3d(options_.initial_sd_m * options_.initial_sd_m,
                                options_.initial_sd_m * options_.initial_sd_m,
                                options_.initial_sd_rad * options_.initial_sd_rad)
                    .asDiagonal();
}

void CorrectionFilter::Predict(const geometry::Pose2& odom_from_body,
                               const std::optional<Eigen::Matrix3d>& reported_covariance) {
  if (last_odom_) {
    // Random-walk drift of the laser odometry: variance proportional to the distance travelled
    // (and, for the heading, to the angle turned).
    const double distance_m =
        std::hypot(odom_from_body.x_m - last_odom_->x_m, odom_from_body.y_m - last_odom_->y_m);
    const double turn_rad =
        std::abs(geometry::NormalizeAngle(odom_from_body.theta_rad - last_odom_->theta_rad));
    const double scale = std::sqrt(noise_scale_);
    const double q_xy = scale * options_.translation_noise_m_per_sqrt_m;
    const double q_th = scale * options_.heading_noise_rad_per_sqrt_m;
    const double q_turn = scale * options_.turn_noise_rad_per_sqrt_rad;
    double grow_xy_m2 = q_xy * q_xy * distance_m;
    double grow_th_rad2 = q_th * q_th * distance_m + q_turn * q_turn * turn_rad;
    // The entity's odometry knows its own sensors: where its covariance grew more than the
    // model says (a real robot's heading drifts far more than the simulated one the defaults
    // were set on), that growth is taken. A correction the entity applied shrinks its
    // covariance: no growth then. Position: the mean of x and y (frames may differ).
    if (reported_covariance && last_reported_ && reported_covariance->allFinite()) {
      const Eigen::Vector3d growth = reported_covariance->diagonal() - last_reported_->diagonal();
      grow_xy_m2 = std::max(grow_xy_m2, 0.5 * (growth.x() + growth.y()));
      grow_th_rad2 = std::max(grow_th_rad2, growth.z());
    }
    covariance_(0, 0) += grow_xy_m2;
    covariance_(1, 1) += grow_xy_m2;
    covariance_(2, 2) += grow_th_rad2;
    covariance_(0, 0) = std::min(covariance_(0, 0), options_.max_sd_m * options_.max_sd_m);
    covariance_(1, 1) = std::min(covariance_(1, 1), options_.max_sd_m * options_.max_sd_m);
    covariance_(2, 2) = std::min(covariance_(2, 2), options_.max_sd_rad * options_.max_sd_rad);
  }
  last_odom_ = odom_from_body;
  if (reported_covariance && reported_covariance->allFinite()) last_reported_ = reported_covariance;
}

void CorrectionFilter::Grow(double factor) {
  covariance_ *= factor;
  const double max_var_m2 = options_.max_sd_m * options_.max_sd_m;
  const double max_var_rad2 = options_.max_sd_rad * options_.max_sd_rad;
  if (covariance_(0, 0) > max_var_m2 || covariance_(1, 1) > max_var_m2 ||
      covariance_(2, 2) > max_var_rad2) {
    covariance_ = Eigen::Vector3d(std::min(covariance_(0, 0), max_var_m2),
                                  std::min(covariance_(1, 1), max_var_m2),
                                  std::min(covariance_(2, 2), max_var_rad2))
                      .asDiagonal();
  }
}

void CorrectionFilter::Adapt(double mahalanobis_sq) {
  if (options_.adapt_window <= 0 || !std::isfinite(mahalanobis_sq)) return;
  recent_mahalanobis_sq_.push_back(mahalanobis_sq);
  if (recent_mahalanobis_sq_.size() < static_cast<std::size_t>(options_.adapt_window)) return;
  std::vector<double>& values = recent_mahalanobis_sq_;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  const double ratio = values[values.size() / 2] / kChi2Median3;
  values.clear();  // the next estimate is made with the rescaled covariances
  const double scale = std::clamp(noise_scale_ * ratio, 1.0, options_.max_noise_scale);
  // The prediction was as far off as the noise: it grows by the same ratio (never shrinks here:
  // the Kalman updates do that).
  if (scale > noise_scale_) Grow(scale / noise_scale_);
  noise_scale_ = scale;
}

scan_matching::SearchWindow CorrectionFilter::Window(
    const scan_matching::SearchWindow& max_window) const {
  scan_matching::SearchWindow window = max_window;
  const double sd_m = std::sqrt(std::max(covariance_(0, 0), covariance_(1, 1)));
  const double sd_rad = std::sqrt(covariance_(2, 2));
  const double xy_m = std::max(options_.min_window_m, 2.0 * options_.window_sigmas * sd_m);
  const double theta_rad = std::max(options_.min_window_rad, 2.0 * options_.window_sigmas * sd_rad);
  window.size_x_m = std::min(max_window.size_x_m, xy_m);
  window.size_y_m = std::min(max_window.size_y_m, xy_m);
  window.size_theta_rad = std::min(max_window.size_theta_rad, theta_rad);
  return window;
}

FilteredCorrection CorrectionFilter::Update(const geometry::Pose2& predicted,
                                            const FusionCorrection& match) {
  FilteredCorrection out;
  out.map_from_body = predicted;
  out.covariance = covariance_;
  const auto precise = [&] {
    return std::sqrt(0.5 * (covariance_(0, 0) + covariance_(1, 1))) < options_.min_update_sd_m;
  };
  if (!match.accepted) {
    out.reason = match.reason;
    if (!precise()) Grow(options_.refused_growth);
    out.covariance = covariance_;
    return out;
  }
  // Measurement covariance in the predicted body frame: residual_sd^2 (J^T J)^-1, with the
  // corridor's axis (a tiny translation eigenvalue) replaced by "no information".
  Eigen::Matrix3d information = match.information;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(information.topLeftCorner<2, 2>());
  const Eigen::Vector2d values = eigen.eigenvalues();  // ascending
  out.constraint_ratio = values(1) > 0.0 ? std::max(values(0), 0.0) / values(1) : 0.0;
  out.degenerate = out.constraint_ratio < options_.degenerate_eigen_ratio;
  information += 1e-9 * Eigen::Matrix3d::Identity() * std::max(information.trace(), 1.0);
  Eigen::Matrix3d measurement = options_.residual_sd_m * options_.residual_sd_m * information.inverse();
  if (out.degenerate) {
    const Eigen::Vector2d weak = eigen.eigenvectors().col(0);
    measurement.topLeftCorner<2, 2>() += kUnconstrainedVariance_m2 * weak * weak.transpose();
  }
  measurement += Eigen::Vector3d(options_.map_sd_m * options_.map_sd_m,
                                 options_.map_sd_m * options_.map_sd_m,
                                 options_.map_sd_rad * options_.map_sd_rad)
                     .asDiagonal();
  measurement = Rotate(measurement, predicted.theta_rad);
  // Innovation in the map frame; every match the matcher accepted tells how well the
  // covariances fit (Adapt), even one that is then not used.
  const geometry::Pose2& z = match.matched_map_from_body;
  const Eigen::Vector3d innovation(z.x_m - predicted.x_m, z.y_m - predicted.y_m,
                                   geometry::NormalizeAngle(z.theta_rad - predicted.theta_rad));
  Adapt(innovation.dot((covariance_ + measurement).inverse() * innovation));
  if (precise()) {
    out.reason = "prediction already within the map's precision";
    out.covariance = covariance_;
    return out;
  }
  // Gated, then the Kalman blend.
  const Eigen::Matrix3d innovation_covariance = covariance_ + measurement;
  const Eigen::Matrix3d inverse = innovation_covariance.inverse();
  out.mahalanobis_sq = innovation.dot(inverse * innovation);
  if (!std::isfinite(out.mahalanobis_sq) || out.mahalanobis_sq > options_.gate_mahalanobis_sq) {
    out.reason = "innovation outside the gate: Mahalanobis^2 " + std::to_string(out.mahalanobis_sq);
    Grow(options_.refused_growth);
    out.covariance = covariance_;
    return out;
  }
  const Eigen::Matrix3d gain = covariance_ * inverse;
  const Eigen::Vector3d step = gain * innovation;
  out.map_from_body = {predicted.x_m + step.x(), predicted.y_m + step.y(),
                       geometry::NormalizeAngle(predicted.theta_rad + step.z())};
  const Eigen::Matrix3d updated = (Eigen::Matrix3d::Identity() - gain) * covariance_;
  covariance_ = 0.5 * (updated + updated.transpose());
  out.covariance = covariance_;
  out.accepted = true;
  return out;
}

}  // namespace pena::fusion
