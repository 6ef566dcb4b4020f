#include "pena/localisation/trajectory_smoother.hpp"

#include <cmath>
#include <string>

#include "pena/options_check.hpp"
#include "pena/slam/pose_graph.hpp"

namespace pena::localisation {
namespace {

using geometry::Pose2;

constexpr double kLooseSigma_m = 100.0;
constexpr double kLooseSigma_rad = 10.0;

void RequirePositive(double value, const char* field, const char* unit) {
  RequireOption(value > 0.0 && std::isfinite(value), "trajectory_smoother", field,
                std::string("> 0 ") + unit, value);
}

void RequireNonNegative(double value, const char* field, const char* unit) {
  RequireOption(value >= 0.0 && std::isfinite(value), "trajectory_smoother", field,
                std::string(">= 0 ") + unit, value);
}

void Validate(const TrajectorySmootherOptions& o) {
  RequirePositive(o.round_sigma_m, "round_sigma_m", "m");
  RequirePositive(o.round_sigma_rad, "round_sigma_rad", "rad");
  RequirePositive(o.degenerate_along_sigma_m, "degenerate_along_sigma_m", "m");
  RequirePositive(o.odometry_sigma_m, "odometry_sigma_m", "m");
  RequirePositive(o.odometry_sigma_rad, "odometry_sigma_rad", "rad");
  RequirePositive(o.start_sigma_m, "start_sigma_m", "m");
  RequirePositive(o.start_sigma_rad, "start_sigma_rad", "rad");
  RequireNonNegative(o.odometry_sigma_per_m, "odometry_sigma_per_m", "m/m");
  RequireNonNegative(o.odometry_sigma_rad_per_rad, "odometry_sigma_rad_per_rad", "rad/rad");
  RequireNonNegative(o.odometry_sigma_rad_per_m, "odometry_sigma_rad_per_m", "rad/m");
  RequireOption(o.max_iterations >= 1, "trajectory_smoother", "max_iterations", ">= 1",
                o.max_iterations);
}

// Information of a pose measurement with sigma `along_m` along `axis_rad` and `across_m` across
// it (the measured pose's frame), and `heading_rad` in heading.
Eigen::Matrix3d Information(double along_m, double across_m, double axis_rad, double heading_rad) {
  const double c = std::cos(axis_rad);
  const double s = std::sin(axis_rad);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  const Eigen::Vector2d inverse_variance(1.0 / (along_m * along_m), 1.0 / (across_m * across_m));
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  information.topLeftCorner<2, 2>() =
      rotation * inverse_variance.asDiagonal() * rotation.transpose();
  information(2, 2) = 1.0 / (heading_rad * heading_rad);
  return information;
}

// The odometry's step between consecutive scans: the growth with the step is why a long stretch
// without rounds gives way to the rounds at its ends.
Eigen::Matrix3d OdometryInformation(const Pose2& step, const TrajectorySmootherOptions& o) {
  const double walked_m = std::hypot(step.x_m, step.y_m);
  const double sigma_m = o.odometry_sigma_m + o.odometry_sigma_per_m * walked_m;
  const double sigma_rad = o.odometry_sigma_rad +
                           o.odometry_sigma_rad_per_rad * std::abs(step.theta_rad) +
                           o.odometry_sigma_rad_per_m * walked_m;
  return Information(sigma_m, sigma_m, 0.0, sigma_rad);
}

// Where the odometry alone put this scan, relative to the plan: the pose before the round's
// correction when a round was accepted here, else the output pose.
const Pose2& Predicted(const LocalisedPose& pose) {
  return pose.correction && pose.correction->accepted ? pose.correction->map_from_body_before
                                                      : pose.map_from_body;
}

slam::PoseEdge RoundEdge(int node, const MapCorrection& round, const TrajectorySmootherOptions& o) {
  const double along_m = round.degenerate ? o.degenerate_along_sigma_m : o.round_sigma_m;
  return {0, node, round.map_from_body_after,
          Information(along_m, o.round_sigma_m, round.weak_axis_rad, o.round_sigma_rad), true};
}

}  // namespace

SmoothedTrajectory SmoothTrajectory(const std::vector<LocalisedPose>& poses,
                                    const TrajectorySmootherOptions& options) {
  Validate(options);
  SmoothedTrajectory result;
  slam::PoseGraph graph;
  graph.AddNode(Pose2{});  // the plan's origin, anchored
  const LocalisedPose* previous = nullptr;
  for (const LocalisedPose& pose : poses) {
    if (!pose.anchored) continue;
    const int node = graph.AddNode(pose.map_from_body);
    result.map_from_body.push_back(pose.map_from_body);
    if (previous == nullptr) {
      graph.AddEdge({0, node, pose.map_from_body,
                     Information(options.start_sigma_m, options.start_sigma_m, 0.0,
                                 options.start_sigma_rad)});
    } else {
      // A relocalisation restarted the odometry: the step there says nothing (a loose edge keeps
      // the graph connected when that round was not accepted).
      const bool restarted = pose.status == MapStatus::kRelocalised && pose.correction;
      const Pose2 step = geometry::Between(previous->map_from_body, Predicted(pose));
      graph.AddEdge({node - 1, node, step,
                     restarted ? Information(kLooseSigma_m, kLooseSigma_m, 0.0, kLooseSigma_rad)
                               : OdometryInformation(step, options)});
    }
    if (pose.correction && pose.correction->accepted) {
      graph.AddEdge(RoundEdge(node, *pose.correction, options));
      ++result.rounds_used;
    }
    previous = &pose;
  }
  result.solved = graph.Optimize(options.max_iterations).solved;
  if (!result.solved) return result;
  for (std::size_t i = 0; i < result.map_from_body.size(); ++i)
    result.map_from_body[i] = graph.nodes()[i + 1];
  return result;
}

}  // namespace pena::localisation
