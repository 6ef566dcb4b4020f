#include "pena/eval/trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pena/eval/rigid_alignment.hpp"

namespace pena::eval {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// Pairs of (estimate index, truth index) at the same instant, in estimate order.
using Matches = std::vector<std::pair<std::size_t, std::size_t>>;

Matches MatchStamps(const geometry::Trajectory& estimate, const geometry::Trajectory& truth,
                    double tolerance_s) {
  Matches matches;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (const auto j = FindStamp(truth, estimate[i].stamp_s, tolerance_s)) {
      matches.emplace_back(i, *j);
    }
  }
  return matches;
}

geometry::Pose2 Alignment(const geometry::Trajectory& estimate, const geometry::Trajectory& truth,
                          const Matches& matches) {
  std::vector<Eigen::Vector2d> estimate_points, truth_points;
  for (const auto& [i, j] : matches) {
    estimate_points.emplace_back(estimate[i].pose.x_m, estimate[i].pose.y_m);
    truth_points.emplace_back(truth[j].pose.x_m, truth[j].pose.y_m);
  }
  return AlignRigid2D(estimate_points, truth_points);
}

double PathLength(const geometry::Trajectory& trajectory, std::size_t from, std::size_t to) {
  double length_m = 0.0;
  for (std::size_t k = from + 1; k <= to; ++k) {
    length_m += std::hypot(trajectory[k].pose.x_m - trajectory[k - 1].pose.x_m,
                           trajectory[k].pose.y_m - trajectory[k - 1].pose.y_m);
  }
  return length_m;
}

}  // namespace

TrajectoryErrorSummary EvaluateAgainstTruth(const geometry::Trajectory& estimate,
                                            const geometry::Trajectory& truth,
                                            const TrajectoryErrorOptions& options) {
  if (!(options.stamp_tolerance_s >= 0.0)) {
    throw std::invalid_argument("trajectory_error.stamp_tolerance_s must be >= 0 s, got " +
                                std::to_string(options.stamp_tolerance_s));
  }
  ValidateTrajectory(estimate, "estimated trajectory");
  ValidateTrajectory(truth, "truth trajectory");
  const Matches matches = MatchStamps(estimate, truth, options.stamp_tolerance_s);
  if (matches.empty()) {
    throw std::invalid_argument("no stamp of the estimated trajectory is within " +
                                std::to_string(options.stamp_tolerance_s) + " s of a truth stamp");
  }
  TrajectoryErrorSummary summary;
  summary.poses_matched = matches.size();
  summary.poses_skipped = estimate.size() - matches.size();
  if (options.align) summary.truth_from_estimate = Alignment(estimate, truth, matches);

  double sum_sq_m2 = 0.0;
  double sum_heading_sq_rad2 = 0.0;
  double last_error_m = 0.0;
  double last_heading_error_deg = 0.0;
  for (const auto& [i, j] : matches) {
    const geometry::Pose2 aligned =
        geometry::Compose(summary.truth_from_estimate, estimate[i].pose);
    const geometry::Pose2& true_pose = truth[j].pose;
    last_error_m = std::hypot(aligned.x_m - true_pose.x_m, aligned.y_m - true_pose.y_m);
    const double heading_error_rad =
        geometry::NormalizeAngle(aligned.theta_rad - true_pose.theta_rad);
    sum_sq_m2 += last_error_m * last_error_m;
    sum_heading_sq_rad2 += heading_error_rad * heading_error_rad;
    last_heading_error_deg = std::abs(heading_error_rad) * kDegPerRad;
    summary.max_heading_error_deg = std::max(summary.max_heading_error_deg, last_heading_error_deg);
    summary.max_translation_error_m = std::max(summary.max_translation_error_m, last_error_m);
  }
  const double n = static_cast<double>(matches.size());
  summary.translation_rmse_m = std::sqrt(sum_sq_m2 / n);
  summary.heading_rmse_deg = std::sqrt(sum_heading_sq_rad2 / n) * kDegPerRad;
  summary.final_position_error_m = last_error_m;
  summary.final_heading_error_deg = last_heading_error_deg;
  // All truth samples between the first and last matched stamp, not only the matched ones: a
  // sparse estimate would otherwise shorten the path to chords and inflate the percentage.
  summary.truth_path_length_m = PathLength(truth, matches.front().second, matches.back().second);
  if (summary.truth_path_length_m > 0.0) {
    summary.final_error_percent_of_path =
        100.0 * summary.final_position_error_m / summary.truth_path_length_m;
  }
  return summary;
}

}  // namespace pena::eval
