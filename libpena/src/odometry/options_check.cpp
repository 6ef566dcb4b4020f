#include "options_check.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"

namespace pena::odometry::internal {
namespace {

void Require(bool ok, const char* field, const char* rule, double value) {
  RequireOption(ok, "laser_odometry", field, rule, value);
}

}  // namespace

const LaserOdometryOptions& CheckedOptions(const LaserOdometryOptions& o) {
  Require(o.window_growth > 1.0, "window_growth", "> 1", o.window_growth);
  Require(o.min_score > 0.0 && o.min_score < 1.0, "min_score", "in (0, 1)", o.min_score);
  Require(o.min_range_m >= 0.0, "min_range_m", ">= 0 m", o.min_range_m);
  Require(o.max_range_m > o.min_range_m, "max_range_m", "> min_range_m (m)", o.max_range_m);
  Require(o.deskew_min_interval_s >= 0.0 && std::isfinite(o.deskew_min_interval_s),
          "deskew_min_interval_s", ">= 0 s and finite", o.deskew_min_interval_s);
  Require(o.deskew_match_passes >= 0 && o.deskew_match_passes <= 10, "deskew_match_passes",
          "in [0, 10]", o.deskew_match_passes);
  Require(o.min_match_points >= 3, "min_match_points", ">= 3 points", o.min_match_points);
  // Built from the constants, so the message follows them.
  static const std::string kLocalMapRule =
      ">= 1, or -1 (auto: " + std::to_string(LaserOdometryOptions::kShortLocalMapKeyframes) +
      " for robots, " + std::to_string(LaserOdometryOptions::kLongLocalMapKeyframes) +
      " for people)";
  Require(o.local_map_keyframes >= 1, "local_map_keyframes", kLocalMapRule.c_str(),
          o.local_map_keyframes);
  Require(o.local_map_pool_keyframes >= LaserOdometryOptions::kAutoPoolKeyframes,
          "local_map_pool_keyframes", ">= 0 (0: off) or -1 (auto: 40 for robots, off for people)",
          o.local_map_pool_keyframes);
  Require(o.local_map_pool_age_s > 0.0, "local_map_pool_age_s", "> 0 s", o.local_map_pool_age_s);
  Require(o.local_map_recent_keyframes >= 1 &&
              o.local_map_recent_keyframes <= o.local_map_keyframes,
          "local_map_recent_keyframes", "in [1, local_map_keyframes]",
          o.local_map_recent_keyframes);
  Require(o.local_map_place_radius_m > 0.0, "local_map_place_radius_m", "> 0 m",
          o.local_map_place_radius_m);
  Require(o.local_map_place_fill_below_score >= 0.0 && o.local_map_place_fill_below_score <= 1.0,
          "local_map_place_fill_below_score", "in [0, 1] (0: off)",
          o.local_map_place_fill_below_score);
  Require(o.local_map_place_fill_frozen_scans >= 0, "local_map_place_fill_frozen_scans",
          ">= 0 scans (0: off)", o.local_map_place_fill_frozen_scans);
  Require(o.keyframe_distance_m > 0.0, "keyframe_distance_m", "> 0 m", o.keyframe_distance_m);
  Require(o.keyframe_angle_rad > 0.0, "keyframe_angle_rad", "> 0 rad", o.keyframe_angle_rad);
  Require(o.keyframe_min_score >= 0.0 && o.keyframe_min_score <= 1.0, "keyframe_min_score",
          "in [0, 1]", o.keyframe_min_score);
  Require(o.frozen_odometry_min_turn_rad >= 0.0, "frozen_odometry_min_turn_rad",
          ">= 0 rad (0: off)", o.frozen_odometry_min_turn_rad);
  Require(o.frozen_odometry_min_move_m >= 0.0, "frozen_odometry_min_move_m", ">= 0 m (0: off)",
          o.frozen_odometry_min_move_m);
  Require(o.degenerate_eigen_ratio >= 0.0 && o.degenerate_eigen_ratio < 1.0,
          "degenerate_eigen_ratio", "in [0, 1)", o.degenerate_eigen_ratio);
  Require(o.pace_check_tolerance >= 0.0 && o.pace_check_tolerance < 1.0, "pace_check_tolerance",
          "in [0, 1) (0: off)", o.pace_check_tolerance);
  Require(o.pace_check_window_m > 0.0 && std::isfinite(o.pace_check_window_m),
          "pace_check_window_m", "> 0 m and finite", o.pace_check_window_m);
  Require(o.pace_check_weak_ratio >= 0.0 && o.pace_check_weak_ratio <= 1.0,
          "pace_check_weak_ratio", "in [0, 1]", o.pace_check_weak_ratio);
  Require((o.degenerate_slide_ratio >= 0.0 && o.degenerate_slide_ratio < 1.0) ||
              o.degenerate_slide_ratio == LaserOdometryOptions::kAutoSlideRatio,
          "degenerate_slide_ratio", "in [0, 1) (0: off) or -1 (auto: 0.2 for people with spread strides)",
          o.degenerate_slide_ratio);
  Require(o.degenerate_max_slide_m > 0.0, "degenerate_max_slide_m", "> 0 m",
          o.degenerate_max_slide_m);
  Require(o.degenerate_slide_max_across_m >= 0.0, "degenerate_slide_max_across_m", ">= 0 m (0: no check)",
          o.degenerate_slide_max_across_m);
  Require(o.degenerate_slide_prior_agreed_m >= 0.0, "degenerate_slide_prior_agreed_m", ">= 0 m (0: no check)",
          o.degenerate_slide_prior_agreed_m);
  Require(o.reference_fill_spacing_m >= 0.0, "reference_fill_spacing_m", ">= 0 m (0: no fill)",
          o.reference_fill_spacing_m);
  Require(o.reference_fill_max_gap_m > 0.0, "reference_fill_max_gap_m", "> 0 m",
          o.reference_fill_max_gap_m);
  Require(o.reference_fill_max_gap_beams >= 0.0, "reference_fill_max_gap_beams",
          ">= 0 (0: no limit)", o.reference_fill_max_gap_beams);
  Require(o.reference_fill_max_gap_beams_bursty >= 0.0, "reference_fill_max_gap_beams_bursty",
          ">= 0 (0: no limit)", o.reference_fill_max_gap_beams_bursty);
  Require(o.timing_burst_gap_s >= 0.0, "timing_burst_gap_s", ">= 0 s (0: no timing check)",
          o.timing_burst_gap_s);
  Require(o.timing_burst_fraction >= 0.0 && o.timing_burst_fraction < 1.0,
          "timing_burst_fraction", "in [0, 1)", o.timing_burst_fraction);
  Require(o.timing_burst_window_scans >= 0, "timing_burst_window_scans",
          ">= 0 scans (0: all so far)", o.timing_burst_window_scans);
  Require(o.prior_gate_rad >= 0.0, "prior_gate_rad", ">= 0 rad (0: no gate)", o.prior_gate_rad);
  Require(o.prior_gate_fraction >= 0.0, "prior_gate_fraction", ">= 0", o.prior_gate_fraction);
  Require(o.prior_gate_fraction_gyro >= 0.0, "prior_gate_fraction_gyro", ">= 0",
          o.prior_gate_fraction_gyro);
  Require(o.prior_gate_m > 0.0, "prior_gate_m", "> 0 m", o.prior_gate_m);
  Require(o.prior_gate_confirm >= 1, "prior_gate_confirm", ">= 1 scans", o.prior_gate_confirm);
  Require(o.prior_gate_confirm_gyro >= 1, "prior_gate_confirm_gyro", ">= 1 scans",
          o.prior_gate_confirm_gyro);
  Require(o.prior_gate_refuse_gyro_rad >= 0.0, "prior_gate_refuse_gyro_rad", ">= 0 rad (0: off)",
          o.prior_gate_refuse_gyro_rad);
  Require(o.prior_gate_compass_window_s >= 0.0, "prior_gate_compass_window_s", ">= 0 s",
          o.prior_gate_compass_window_s);
  Require(o.stale_history_scans >= 0, "stale_history_scans", ">= 0 scans (0: no check)",
          o.stale_history_scans);
  Require(o.stale_repeat_m >= 0.0, "stale_repeat_m", ">= 0 m", o.stale_repeat_m);
  Require(o.stale_changed_m >= o.stale_repeat_m, "stale_changed_m", ">= stale_repeat_m (m)",
          o.stale_changed_m);
  const PoseCovarianceOptions& c = o.covariance;
  Require(c.motion_m_per_sqrt_m >= 0.0, "covariance.motion_m_per_sqrt_m", ">= 0 m/sqrt(m)",
          c.motion_m_per_sqrt_m);
  Require(c.motion_rad_per_sqrt_m >= 0.0, "covariance.motion_rad_per_sqrt_m", ">= 0 rad/sqrt(m)",
          c.motion_rad_per_sqrt_m);
  Require(c.motion_rad_per_sqrt_rad >= 0.0, "covariance.motion_rad_per_sqrt_rad",
          ">= 0 rad/sqrt(rad)", c.motion_rad_per_sqrt_rad);
  Require(c.match_residual_sd_m > 0.0, "covariance.match_residual_sd_m", "> 0 m",
          c.match_residual_sd_m);
  Require(c.match_min_sd_m >= 0.0, "covariance.match_min_sd_m", ">= 0 m", c.match_min_sd_m);
  Require(c.match_min_sd_rad >= 0.0, "covariance.match_min_sd_rad", ">= 0 rad", c.match_min_sd_rad);
  Require(c.gate_trusted_disagreement_share >= 0.0 && c.gate_trusted_disagreement_share <= 1.0,
          "covariance.gate_trusted_disagreement_share", "in [0, 1]",
          c.gate_trusted_disagreement_share);
  Require(c.weak_ratio >= 0.0 && c.weak_ratio <= 1.0, "covariance.weak_ratio", "in [0, 1]",
          c.weak_ratio);
  Require(c.weak_disagreement_share >= 0.0, "covariance.weak_disagreement_share", ">= 0",
          c.weak_disagreement_share);
  scan_matching::ValidateWindow(o.window, o.matcher);
  scan_matching::ValidateWindow(o.wide_window, o.matcher);
  return o;
}

}  // namespace pena::odometry::internal
