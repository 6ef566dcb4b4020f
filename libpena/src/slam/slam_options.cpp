#include "pena/slam/slam_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"

namespace pena::slam {
namespace {

void RequirePositive(double value, const char* field, const char* unit) {
  RequireOption(value > 0.0 && std::isfinite(value), "slam", field, std::string("> 0 ") + unit,
                value);
}

void RequireNonNegative(double value, const char* field, const char* unit) {
  RequireOption(value >= 0.0 && std::isfinite(value), "slam", field,
                std::string(">= 0 ") + unit + " and finite", value);
}

}  // namespace

SlamOptions ForEntity(SlamOptions options, sensors::EntityKind kind) {
  if (options.loop_wide_window_m == SlamOptions::kAutoWideWindow) {
    options.loop_wide_window_m =
        kind == sensors::EntityKind::kRobot ? SlamOptions::kRobotWideWindowM : 0.0;
  }
  return options;
}

void ValidateSlamOptions(const SlamOptions& o) {
  RequirePositive(o.keyframe_distance_m, "keyframe_distance_m", "m");
  RequirePositive(o.keyframe_angle_rad, "keyframe_angle_rad", "rad");
  RequireNonNegative(o.min_range_m, "min_range_m", "m");
  RequirePositive(o.max_range_m - o.min_range_m, "max_range_m - min_range_m", "m");
  RequireNonNegative(o.loop_min_path_m, "loop_min_path_m", "m");
  RequireOption(o.submap_keyframes >= 0, "slam", "submap_keyframes", ">= 0", o.submap_keyframes);
  RequireOption(o.loop_check_every >= 1, "slam", "loop_check_every", ">= 1", o.loop_check_every);
  RequireOption(o.optimize_iterations >= 1, "slam", "optimize_iterations", ">= 1",
                o.optimize_iterations);
  RequirePositive(o.submap_radius_m, "submap_radius_m", "m");
  RequirePositive(o.loop_window_m, "loop_window_m", "m");
  RequireNonNegative(o.loop_window_per_m, "loop_window_per_m", "m/m");
  RequirePositive(o.loop_window_max_m, "loop_window_max_m", "m");
  RequirePositive(o.loop_window_rad, "loop_window_rad", "rad");
  RequireNonNegative(o.loop_window_rad_per_m, "loop_window_rad_per_m", "rad/m");
  RequirePositive(o.loop_window_max_rad, "loop_window_max_rad", "rad");
  RequireOption(o.loop_min_score > 0.0 && o.loop_min_score <= 1.0, "slam", "loop_min_score",
                "in (0, 1]", o.loop_min_score);
  RequireOption((o.loop_wide_window_m >= 0.0 && std::isfinite(o.loop_wide_window_m)) ||
                    o.loop_wide_window_m == SlamOptions::kAutoWideWindow,
                "slam", "loop_wide_window_m", ">= 0 m (or -1: by entity kind)", o.loop_wide_window_m);
  RequireNonNegative(o.loop_wide_min_path_m, "loop_wide_min_path_m", "m");
  RequireOption(o.loop_wide_check_every >= 1, "slam", "loop_wide_check_every", ">= 1",
                o.loop_wide_check_every);
  RequireNonNegative(o.degenerate_eigen_ratio, "degenerate_eigen_ratio", "(ratio)");
  RequirePositive(o.odometry_sigma_m, "odometry_sigma_m", "m");
  RequireNonNegative(o.odometry_sigma_per_m, "odometry_sigma_per_m", "m/m");
  RequirePositive(o.odometry_sigma_rad, "odometry_sigma_rad", "rad");
  RequireNonNegative(o.odometry_sigma_rad_per_m, "odometry_sigma_rad_per_m", "rad/m");
  RequirePositive(o.loop_sigma_m, "loop_sigma_m", "m");
  RequirePositive(o.loop_sigma_rad, "loop_sigma_rad", "rad");
  RequireNonNegative(o.loop_weak_sigma_max_m, "loop_weak_sigma_max_m", "m");
  RequirePositive(o.max_loop_chi2, "max_loop_chi2", "(chi2)");
}

}  // namespace pena::slam
