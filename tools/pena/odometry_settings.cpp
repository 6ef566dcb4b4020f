#include "odometry_settings.hpp"

#include <map>
#include <stdexcept>

#include "cli_support.hpp"

namespace pena::cli {
namespace {

// The numeric options --set may change (names as in LaserOdometryOptions).
std::map<std::string, double*> SettableOptions(odometry::LaserOdometryOptions& o) {
  return {{"min_score", &o.min_score},
          {"keyframe_distance_m", &o.keyframe_distance_m},
          {"keyframe_angle_rad", &o.keyframe_angle_rad},
          {"keyframe_min_score", &o.keyframe_min_score},
          {"local_map_pool_age_s", &o.local_map_pool_age_s},
          {"local_map_place_radius_m", &o.local_map_place_radius_m},
          {"local_map_place_fill_below_score", &o.local_map_place_fill_below_score},
          {"frozen_odometry_min_turn_rad", &o.frozen_odometry_min_turn_rad},
          {"frozen_odometry_min_move_m", &o.frozen_odometry_min_move_m},
          {"degenerate_eigen_ratio", &o.degenerate_eigen_ratio},
          {"pace_check_tolerance", &o.pace_check_tolerance},
          {"pace_check_window_m", &o.pace_check_window_m},
          {"pace_check_weak_ratio", &o.pace_check_weak_ratio},
          {"degenerate_slide_ratio", &o.degenerate_slide_ratio},
          {"degenerate_max_slide_m", &o.degenerate_max_slide_m},
          {"degenerate_slide_max_across_m", &o.degenerate_slide_max_across_m},
          {"degenerate_slide_prior_agreed_m", &o.degenerate_slide_prior_agreed_m},
          {"covariance.motion_m_per_sqrt_m", &o.covariance.motion_m_per_sqrt_m},
          {"covariance.motion_rad_per_sqrt_m", &o.covariance.motion_rad_per_sqrt_m},
          {"covariance.motion_rad_per_sqrt_rad", &o.covariance.motion_rad_per_sqrt_rad},
          {"covariance.match_residual_sd_m", &o.covariance.match_residual_sd_m},
          {"covariance.match_min_sd_m", &o.covariance.match_min_sd_m},
          {"covariance.match_min_sd_rad", &o.covariance.match_min_sd_rad},
          {"covariance.gate_trusted_disagreement_share",
           &o.covariance.gate_trusted_disagreement_share},
          {"covariance.weak_ratio", &o.covariance.weak_ratio},
          {"covariance.weak_disagreement_share", &o.covariance.weak_disagreement_share},
          {"reference_fill_spacing_m", &o.reference_fill_spacing_m},
          {"reference_fill_max_gap_m", &o.reference_fill_max_gap_m},
          {"reference_fill_max_gap_beams", &o.reference_fill_max_gap_beams},
          {"reference_fill_max_gap_beams_bursty", &o.reference_fill_max_gap_beams_bursty},
          {"timing_burst_gap_s", &o.timing_burst_gap_s},
          {"deskew_min_interval_s", &o.deskew_min_interval_s},
          {"timing_burst_fraction", &o.timing_burst_fraction},
          {"prior_gate_rad", &o.prior_gate_rad},
          {"prior_gate_fraction", &o.prior_gate_fraction},
          {"prior_gate_fraction_gyro", &o.prior_gate_fraction_gyro},
          {"prior_gate_m", &o.prior_gate_m},
          {"prior_gate_refuse_gyro_rad", &o.prior_gate_refuse_gyro_rad},
          {"prior_gate_compass_window_s", &o.prior_gate_compass_window_s},
          {"stale_repeat_m", &o.stale_repeat_m},
          {"stale_changed_m", &o.stale_changed_m},
          {"matcher.threshold_m", &o.matcher.threshold_m},
          {"dead_reckoning.max_stride_period_s", &o.dead_reckoning.max_stride_period_s},
          {"dead_reckoning.stopped_after_periods", &o.dead_reckoning.stopped_after_periods},
          {"dead_reckoning.unreported_pace_m_s", &o.dead_reckoning.unreported_pace_m_s},
          {"dead_reckoning.stopped_stride_fraction", &o.dead_reckoning.stopped_stride_fraction},
          {"dead_reckoning.turning_on_the_spot_rad_s",
           &o.dead_reckoning.turning_on_the_spot_rad_s},
          {"dead_reckoning.overdue_turn_rad", &o.dead_reckoning.overdue_turn_rad},
          {"dead_reckoning.stride_interpolation.max_hold_s",
           &o.dead_reckoning.stride_interpolation.max_hold_s},
          {"dead_reckoning.stride_interpolation.max_stride_period_s",
           &o.dead_reckoning.stride_interpolation.max_stride_period_s},
          {"dead_reckoning.stride_interpolation.default_stride_period_s",
           &o.dead_reckoning.stride_interpolation.default_stride_period_s},
          {"dead_reckoning.stride_calibration.interval_m",
           &o.dead_reckoning.stride_calibration.interval_m},
          {"dead_reckoning.stride_calibration.prior_weight_m2",
           &o.dead_reckoning.stride_calibration.prior_weight_m2},
          {"dead_reckoning.stride_calibration.max_correction",
           &o.dead_reckoning.stride_calibration.max_correction}};
}

}  // namespace

void ApplyOdometrySettings(const std::vector<std::string>& settings,
                           odometry::LaserOdometryOptions& o) {
  SettingTargets targets;
  targets.doubles = SettableOptions(o);
  targets.ints = {{"local_map_keyframes", &o.local_map_keyframes},
                  {"deskew_match_passes", &o.deskew_match_passes},
                  {"local_map_pool_keyframes", &o.local_map_pool_keyframes},
                  {"local_map_place_fill_frozen_scans", &o.local_map_place_fill_frozen_scans},
                  {"local_map_recent_keyframes", &o.local_map_recent_keyframes},
                  {"min_match_points", &o.min_match_points},
                  {"prior_gate_confirm", &o.prior_gate_confirm},
                  {"prior_gate_confirm_gyro", &o.prior_gate_confirm_gyro},
                  {"stale_history_scans", &o.stale_history_scans},
                  {"timing_burst_window_scans", &o.timing_burst_window_scans}};
  targets.flags = {
      {"dead_reckoning.stride_calibration.enabled", &o.dead_reckoning.stride_calibration.enabled},
      {"dead_reckoning.stride_interpolation.enabled",
       &o.dead_reckoning.stride_interpolation.enabled},
      {"degenerate_slide_backward_only", &o.degenerate_slide_backward_only},
      {"deskew_scans", &o.deskew_scans},
      {"deskew_bursty_scans", &o.deskew_bursty_scans}};
  for (const std::string& text : settings) {
    const Setting setting = ParseSetting(text);
    if (!ApplySetting(targets, setting)) {
      throw std::runtime_error("--set: unknown option '" + setting.name + "' (see docs/odometry.md)");
    }
  }
}

}  // namespace pena::cli
