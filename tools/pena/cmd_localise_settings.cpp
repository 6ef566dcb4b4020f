// `pena localise --set NAME=VALUE`: the names of the plan-matching, global-start, plan-adaptation
// and smoother options (docs/localisation.md, "pena localise").
#include <string>
#include <string_view>
#include <vector>

#include "cli_support.hpp"
#include "cmd_localise.hpp"
#include "odometry_settings.hpp"

namespace pena::cli::localise {

// Applies --set NAME=VALUE to the plan-matching options (names as in MapLocaliserOptions) and,
// prefixed "odometry.", to the odometry underneath (the names of `pena odometry --set`), and
// global.compass_tolerance_deg (PlanLocalisationOptions::compass_tolerance_rad, in degrees),
// global.freeze_history_keyframes, global.boundary_fraction, global.freeze_ranking,
// global.answer_on_plan (0/1), global.return_fit_keyframes, global.min_followed_keyframes,
// global.min_decide_return_fraction, global.min_decide_return_keyframes and global.min_travel_m
// (GlobalTrackerOptions),
// global.agreement_tolerance_m (GlobalLocaliserOptions), relocalise_after_rounds
// (PlanLocalisationOptions, plan rounds; 0 = off), plan_adaptation.* (PlanAdaptationOptions) and
// lost.* (LostAndFoundOptions);
// integer options are rounded; unknown names are errors. The values are validated by the
// pipeline (its constructor and SetPlan).
void ApplySettings(const std::vector<std::string>& settings, pipeline::EntityPipelineOptions& options) {
  pipeline::PlanLocalisationOptions& plan = options.plan_localisation;
  localisation::MapLocaliserOptions& o = plan.map;
  constexpr std::string_view kOdometry = "odometry.";
  constexpr std::string_view kSmooth = "smooth.";
  std::vector<std::string> odometry_settings;
  SettingTargets targets;
  targets.doubles = {{"min_score", &o.min_score},
                     {"reacquire_min_score", &o.reacquire_min_score},
                     {"window_growth", &o.window_growth},
                     {"max_range_m", &o.max_range_m},
                     {"degenerate_eigen_ratio", &o.degenerate_eigen_ratio},
                     {"along_probe_m", &o.along_probe_m},
                     {"along_min_drop", &o.along_min_drop},
                     {"recast_min_m", &o.recast_min_m},
                     {"recast_min_rad", &o.recast_min_rad},
                     {"along_search_m", &o.along_search_m},
                     {"along_search_step_m", &o.along_search_step_m},
                     {"matcher.threshold_m", &o.matcher.threshold_m},
                     {"plan_adaptation.association_m", &o.plan_adaptation.association_m},
                     {"plan_adaptation.end_margin_m", &o.plan_adaptation.end_margin_m},
                     {"plan_adaptation.min_other_information", &o.plan_adaptation.min_other_information},
                     {"plan_adaptation.min_offset_m", &o.plan_adaptation.min_offset_m},
                     {"plan_adaptation.max_spread_m", &o.plan_adaptation.max_spread_m},
                     {"plan_adaptation.wall_sigma_m", &o.plan_adaptation.wall_sigma_m},
                     {"plan_adaptation.prior_sigma_m", &o.plan_adaptation.prior_sigma_m},
                     {"plan_adaptation.prior_sigma_per_m", &o.plan_adaptation.prior_sigma_per_m},
                     {"plan_adaptation.prior_facing_sigma_m", &o.plan_adaptation.prior_facing_sigma_m},
                     {"plan_adaptation.openings.through_margin_m", &o.plan_adaptation.openings.through_margin_m},
                     {"plan_adaptation.openings.bin_m", &o.plan_adaptation.openings.bin_m},
                     {"plan_adaptation.openings.min_width_m", &o.plan_adaptation.openings.min_width_m},
                     {"plan_adaptation.openings.hit_m", &o.plan_adaptation.openings.hit_m},
                     {"plan_adaptation.ends.join_m", &o.plan_adaptation.ends.join_m},
                     {"plan_adaptation.ends.across_m", &o.plan_adaptation.ends.across_m},
                     {"plan_adaptation.ends.window_m", &o.plan_adaptation.ends.window_m},
                     {"plan_adaptation.ends.max_gap_m", &o.plan_adaptation.ends.max_gap_m},
                     {"plan_adaptation.ends.past_rad", &o.plan_adaptation.ends.past_rad},
                     {"plan_adaptation.ends.past_m", &o.plan_adaptation.ends.past_m},
                     {"plan_adaptation.ends.max_spread_m", &o.plan_adaptation.ends.max_spread_m},
                     {"plan_adaptation.ends.min_error_m", &o.plan_adaptation.ends.min_error_m},
                     {"global.boundary_fraction", &plan.tracker.boundary_fraction},
                     {"global.agreement_tolerance_m", &plan.global.agreement_tolerance_m},
                     {"global.min_decide_return_fraction", &plan.tracker.min_decide_return_fraction},
                     {"global.min_travel_m", &plan.tracker.min_travel_m},
                     {"lost.lost_explained_fraction", &plan.lost.lost_explained_fraction},
                     {"lost.lost_sigma_m", &plan.lost.lost_sigma_m},
                     {"lost.region_start_m", &plan.lost.region_start_m},
                     {"lost.region_growth", &plan.lost.region_growth},
                     {"lost.search_every_m", &plan.lost.search_every_m},
                     {"lost.found_explained_fraction", &plan.lost.found_explained_fraction},
                     {"lost.found_margin", &plan.lost.found_margin}};
  targets.ints = {{"min_hits", &o.min_hits},
                  {"outside_after_failures", &o.outside_after_failures},
                  {"oversample", &o.oversample},
                  {"global.freeze_history_keyframes", &plan.tracker.freeze_history_keyframes},
                  {"global.freeze_ranking", &plan.tracker.freeze_ranking},
                  {"global.return_fit_keyframes", &plan.tracker.return_fit_keyframes},
                  {"global.min_followed_keyframes", &plan.tracker.min_followed_keyframes},
                  {"global.min_decide_return_keyframes", &plan.tracker.min_decide_return_keyframes},
                  {"relocalise_after_rounds", &plan.relocalise_after_rounds},
                  {"plan_adaptation.min_points", &o.plan_adaptation.min_points},
                  {"plan_adaptation.min_rounds", &o.plan_adaptation.min_rounds},
                  {"plan_adaptation.openings.min_through_points", &o.plan_adaptation.openings.min_through_points},
                  {"plan_adaptation.openings.min_rounds", &o.plan_adaptation.openings.min_rounds},
                  {"plan_adaptation.ends.min_points", &o.plan_adaptation.ends.min_points},
                  {"plan_adaptation.ends.min_ends", &o.plan_adaptation.ends.min_ends},
                  {"lost.lost_after_rounds", &plan.lost.lost_after_rounds},
                  {"lost.max_candidates", &plan.lost.max_candidates},
                  {"lost.confirm_keyframes", &plan.lost.confirm_keyframes}};
  targets.flags = {{"global.answer_on_plan", &plan.tracker.answer_on_plan},
                   {"reacquire_pinned", &o.reacquire_pinned},
                   {"require_interior", &o.require_interior},
                   {"along_search_failed", &o.along_search_failed},
                   {"along_search_unique", &o.along_search_unique},
                   {"plan_adaptation.enabled", &o.plan_adaptation.enabled},
                   {"plan_adaptation.openings.enabled", &o.plan_adaptation.openings.enabled},
                   {"plan_adaptation.ends.enabled", &o.plan_adaptation.ends.enabled},
                   {"lost.enabled", &plan.lost.enabled}};
  for (const std::string& text : settings) {
    if (text.starts_with(kSmooth)) continue;  // SmootherOptions, with --smooth
    if (text.starts_with(kOdometry)) {
      odometry_settings.push_back(text.substr(kOdometry.size()));
      continue;
    }
    const Setting setting = ParseSetting(text);
    if (setting.name == "global.compass_tolerance_deg") {
      plan.compass_tolerance_rad = setting.value * kDeg;
    } else if (setting.name == "window.size_xy_m") {
      o.window.size_x_m = o.window.size_y_m = setting.value;
    } else if (setting.name == "max_window.size_xy_m") {
      o.max_window.size_x_m = o.max_window.size_y_m = setting.value;
    } else if (!ApplySetting(targets, setting)) {
      throw std::runtime_error("--set: unknown option '" + setting.name + "' (see docs/localisation.md)");
    }
  }
  ApplyOdometrySettings(odometry_settings, options.odometry);
}

// Applies --set smooth.NAME=VALUE to the offline smoother (names as in TrajectorySmootherOptions,
// validated by SmoothTrajectory); unknown names are errors.
localisation::TrajectorySmootherOptions SmootherOptions(const std::vector<std::string>& settings) {
  localisation::TrajectorySmootherOptions o;
  SettingTargets targets;
  targets.doubles = {
      {"smooth.round_sigma_m", &o.round_sigma_m},
      {"smooth.degenerate_along_sigma_m", &o.degenerate_along_sigma_m},
      {"smooth.odometry_sigma_m", &o.odometry_sigma_m},
      {"smooth.odometry_sigma_per_m", &o.odometry_sigma_per_m},
      {"smooth.odometry_sigma_rad", &o.odometry_sigma_rad},
      {"smooth.odometry_sigma_rad_per_rad", &o.odometry_sigma_rad_per_rad},
      {"smooth.odometry_sigma_rad_per_m", &o.odometry_sigma_rad_per_m},
      {"smooth.start_sigma_m", &o.start_sigma_m}};
  for (const std::string& text : settings) {
    if (!text.starts_with("smooth.")) continue;
    const Setting setting = ParseSetting(text);
    if (setting.name == "smooth.round_sigma_deg") {
      o.round_sigma_rad = setting.value * kDeg;
    } else if (!ApplySetting(targets, setting)) {
      throw std::runtime_error("--set: unknown option '" + setting.name + "' (see docs/localisation.md)");
    }
  }
  return o;
}

}  // namespace pena::cli::localise
