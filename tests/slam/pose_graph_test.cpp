// The pose graph: Gauss-Newton on a drifted square loop closed by one edge.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pena/slam/pose_graph.hpp"

namespace pena::slam {
namespace {

using geometry::Pose2;

// A 4 m x 4 m square walked counter-clockwise in 0.5 m steps (32 poses, back at the start).
std::vector<Pose2> SquareLoop() {
  std::vector<Pose2> poses;
  Pose2 pose;
  for (int side = 0; side < 4; ++side) {
    for (int step = 0; step < 8; ++step) {
      poses.push_back(pose);
      const bool corner = step == 7;
      pose = geometry::Compose(pose, {0.5, 0.0, corner ? std::numbers::pi / 2.0 : 0.0});
    }
  }
  poses.push_back(pose);  // pose 32 = pose 0 again
  return poses;
}

Eigen::Matrix3d Information(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d(1 / (sigma_m * sigma_m), 1 / (sigma_m * sigma_m),
                         1 / (sigma_rad * sigma_rad))
      .asDiagonal();
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

// Odometry edges with a heading bias of 0.02 rad per step, chained into the initial estimate.
PoseGraph DriftedSquare(const std::vector<Pose2>& truth) {
  PoseGraph graph;
  graph.AddNode(truth[0]);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    Pose2 motion = geometry::Between(truth[i - 1], truth[i]);
    motion.theta_rad += 0.02;
    graph.AddNode(geometry::Compose(graph.nodes().back(), motion));
    graph.AddEdge({static_cast<int>(i - 1), static_cast<int>(i), motion, Information(0.05, 0.02),
                   false});
  }
  return graph;
}

TEST(PoseGraph, ClosingTheLoopRemovesMostOfTheDrift) {
  const std::vector<Pose2> truth = SquareLoop();
  PoseGraph graph = DriftedSquare(truth);
  const int last = static_cast<int>(truth.size()) - 1;
  const double drift_before_m = Distance(graph.nodes().back(), truth.back());
  ASSERT_GT(drift_before_m, 1.0);
  graph.AddEdge({0, last, geometry::Between(truth[0], truth.back()), Information(0.01, 0.005),
                 false});
  const OptimizeResult result = graph.Optimize(20);
  ASSERT_TRUE(result.solved);
  EXPECT_LT(result.final_chi2, result.initial_chi2);
  EXPECT_LT(Distance(graph.nodes().back(), truth.back()), 0.05);
  double worst_m = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst_m = std::max(worst_m, Distance(graph.nodes()[i], truth[i]));
  }
  EXPECT_LT(worst_m, 0.5);  // the bias is spread over the loop, not removed
}

TEST(PoseGraph, KeepsTheFirstNodeWhereItIs) {
  const std::vector<Pose2> truth = SquareLoop();
  PoseGraph graph = DriftedSquare(truth);
  graph.AddEdge({0, static_cast<int>(truth.size()) - 1, {0.3, -0.2, 0.1}, Information(0.01, 0.005),
                 false});
  graph.Optimize(10);
  EXPECT_NEAR(graph.nodes()[0].x_m, 0.0, 1e-6);
  EXPECT_NEAR(graph.nodes()[0].y_m, 0.0, 1e-6);
  EXPECT_NEAR(graph.nodes()[0].theta_rad, 0.0, 1e-6);
}

TEST(PoseGraph, EdgeErrorIsZeroForTheMeasuredMotion) {
  const Pose2 from{1.0, 2.0, 0.7};
  const Pose2 motion{0.4, -0.3, 0.2};
  const Eigen::Vector3d error = EdgeError(from, geometry::Compose(from, motion), motion);
  EXPECT_NEAR(error.norm(), 0.0, 1e-12);
}

TEST(PoseGraph, RefusesAnEdgeToAMissingNode) {
  PoseGraph graph;
  graph.AddNode({});
  EXPECT_THROW(graph.AddEdge({0, 1, {}, Eigen::Matrix3d::Identity(), false}),
               std::invalid_argument);
  EXPECT_THROW(graph.AddEdge({0, 0, {}, Eigen::Matrix3d::Identity(), false}),
               std::invalid_argument);
}

TEST(PoseGraph, RobustClosureBendsTheGraphLessThanAPlainOne) {
  const std::vector<Pose2> truth = SquareLoop();
  const int last = static_cast<int>(truth.size()) - 1;
  const Pose2 wrong{2.0, 1.5, 0.0};  // a false closure, 2.5 m off
  PoseGraph plain = DriftedSquare(truth);
  PoseGraph robust = DriftedSquare(truth);
  plain.AddEdge({0, last, wrong, Information(0.05, 0.01), false});
  robust.AddEdge({0, last, wrong, Information(0.05, 0.01), true});
  plain.Optimize(20);
  robust.Optimize(20);
  const Pose2 unbent = DriftedSquare(truth).nodes().back();
  EXPECT_LT(Distance(robust.nodes().back(), unbent), Distance(plain.nodes().back(), unbent));
}

// A straight 9 m walk whose odometry drifts 5 cm sideways per metre with a correct heading, closed
// by an edge that puts the end back on the line. Without heading priors the graph rotates the
// walk to meet it; with them (a compass-bounded heading) it moves the positions instead.
TEST(PoseGraph, HeadingPriorsKeepTheHeadingsWhileAClosureMovesPositions) {
  auto solve = [](bool priors) {
    PoseGraph graph;
    graph.AddNode({0.0, 0.0, 0.0});
    const Pose2 step{1.0, 0.05, 0.0};
    for (int i = 1; i <= 9; ++i) {
      graph.AddNode(geometry::Compose(graph.nodes().back(), step));
      graph.AddEdge({i - 1, i, step, Information(0.05, 0.01), false});
      if (priors) graph.AddHeadingPrior({i, 0.0, 1.0 / (0.002 * 0.002)});
    }
    graph.AddEdge({0, 9, {9.0, 0.0, 0.0}, Information(0.01, 0.01), false});
    EXPECT_TRUE(graph.Optimize(20).solved);
    double max_heading_rad = 0.0;
    for (const Pose2& node : graph.nodes()) {
      max_heading_rad = std::max(max_heading_rad, std::abs(node.theta_rad));
    }
    EXPECT_LT(Distance(graph.nodes().back(), {9.0, 0.0, 0.0}), 0.05) << "priors " << priors;
    return max_heading_rad;
  };
  const double free_rad = solve(false);
  const double held_rad = solve(true);
  EXPECT_GT(free_rad, 0.01);  // the closure bent the walk
  EXPECT_LT(held_rad, 0.2 * free_rad);
}

TEST(PoseGraph, RefusesAHeadingPriorOnAMissingNodeOrWithoutInformation) {
  PoseGraph graph;
  graph.AddNode({});
  EXPECT_THROW(graph.AddHeadingPrior({1, 0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(graph.AddHeadingPrior({0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(graph.AddHeadingPrior({0, std::nan(""), 1.0}), std::invalid_argument);
  EXPECT_NO_THROW(graph.AddHeadingPrior({0, 0.1, 1.0}));
  EXPECT_EQ(graph.heading_priors().size(), 1u);
}

}  // namespace
}  // namespace pena::slam
