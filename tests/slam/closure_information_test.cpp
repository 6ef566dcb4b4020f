// How far a loop closure is trusted each way (slam::internal::ClosureInformation): a corridor
// closure holds across the corridor and lets the along position go, in the pose graph's own edge
// frame, whatever the two keyframes' headings.
#include "pena/slam/internal/edge_information.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "pena/slam/pose_graph.hpp"

namespace pena::slam::internal {
namespace {

using geometry::Pose2;

// A match along a corridor that runs along the centre keyframe's x: J^T J is 25 times weaker
// along it than across, so the along sigma is 5 x loop_sigma_m.
LoopMatch CorridorMatch(double measured_theta_rad) {
  LoopMatch match;
  match.centre_from_scan = {1.0, 0.0, measured_theta_rad};
  match.information = Eigen::Vector3d(4.0, 100.0, 50.0).asDiagonal();
  return match;
}

SlamOptions Shaped() {
  SlamOptions options;
  options.loop_sigma_m = 0.05;
  options.loop_weak_sigma_max_m = 1.0;
  return options;
}

// The chi2 of the closure edge once the new keyframe is moved by `shift_centre` (centre frame)
// from where the match put it; the centre keyframe stands at `centre` in the world.
double Chi2AfterShift(const LoopMatch& match, const SlamOptions& options, const Pose2& centre,
                      const Eigen::Vector2d& shift_centre) {
  PoseGraph graph;
  graph.AddNode(centre);
  Pose2 moved = match.centre_from_scan;
  moved.x_m += shift_centre.x();
  moved.y_m += shift_centre.y();
  graph.AddNode(geometry::Compose(centre, moved));
  const PoseEdge edge{0, 1, match.centre_from_scan, ClosureInformation(match, options), true};
  return graph.EdgeChi2(edge);
}

TEST(ClosureInformation, OffIsTheSameSigmaBothWays) {
  SlamOptions options;
  options.loop_weak_sigma_max_m = 0.0;
  const Eigen::Matrix3d information = ClosureInformation(CorridorMatch(0.0), options);
  EXPECT_DOUBLE_EQ(information(0, 0), 1.0 / (options.loop_sigma_m * options.loop_sigma_m));
  EXPECT_DOUBLE_EQ(information(1, 1), 1.0 / (options.loop_sigma_m * options.loop_sigma_m));
  EXPECT_DOUBLE_EQ(information(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(information(2, 2), 1.0 / (options.loop_sigma_rad * options.loop_sigma_rad));
}

TEST(ClosureInformation, ACorridorClosureLetsTheAlongPositionGoInTheGraphsEdgeFrame) {
  // Headings of the centre keyframe and of the match (opposite walking directions, a right
  // angle, any): one sigma is 0.25 m along the corridor and 0.05 m across, in the centre frame.
  for (const double centre_rad : {0.0, 0.5, -2.0}) {
    for (const double measured_rad : {0.0, std::numbers::pi / 2.0, std::numbers::pi, 1.0}) {
      const LoopMatch match = CorridorMatch(measured_rad);
      const Pose2 centre{3.0, -2.0, centre_rad};
      SCOPED_TRACE("centre " + std::to_string(centre_rad) + " rad, measured " +
                   std::to_string(measured_rad) + " rad");
      EXPECT_NEAR(Chi2AfterShift(match, Shaped(), centre, {0.25, 0.0}), 1.0, 1e-6);
      EXPECT_NEAR(Chi2AfterShift(match, Shaped(), centre, {0.0, 0.05}), 1.0, 1e-6);
      EXPECT_NEAR(Chi2AfterShift(match, Shaped(), centre, {0.05, 0.0}), 0.04, 1e-6);
    }
  }
}

TEST(ClosureInformation, TheWeakSigmaIsCappedAlsoWithoutAnyInformationAlong) {
  SlamOptions options = Shaped();
  options.loop_weak_sigma_max_m = 0.2;  // below the 0.25 m the ratio asks for
  const Pose2 centre{0.0, 0.0, 0.0};
  EXPECT_NEAR(Chi2AfterShift(CorridorMatch(0.0), options, centre, {0.2, 0.0}), 1.0, 1e-6);
  LoopMatch featureless = CorridorMatch(0.0);
  featureless.information(0, 0) = 0.0;
  EXPECT_NEAR(Chi2AfterShift(featureless, options, centre, {0.2, 0.0}), 1.0, 1e-6);
  EXPECT_NEAR(Chi2AfterShift(featureless, options, centre, {0.0, 0.05}), 1.0, 1e-6);
}

}  // namespace
}  // namespace pena::slam::internal
