#include "pena/scan_matching/correlation_scan_matcher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "synthetic_room.hpp"

namespace pena::scan_matching {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Pair {
  Points2 reference;
  Points2 scan;
  geometry::Pose2 reference_from_scan;  // the truth
};

// Two scans of the synthetic room: the reference from `a`, the scan from `b`.
Pair MakePair(const geometry::Pose2& world_from_a, const geometry::Pose2& world_from_b,
              double noise_m, unsigned seed) {
  std::mt19937 rng(seed);
  const auto walls = testing::SyntheticRoom();
  return {testing::ScanRoom(walls, world_from_a, noise_m, rng),
          testing::ScanRoom(walls, world_from_b, noise_m, rng),
          geometry::Between(world_from_a, world_from_b)};
}

TEST(CorrelationScanMatcher, RecoversKnownMotionWithPaperWindow) {
  const Pair pair = MakePair({1.5, 2.5, 0.0}, {1.62, 2.44, 1.2 * kDeg}, 0.01, 1);
  const CorrelationScanMatcher matcher({}, pair.reference);
  // Prior: dead reckoning without the true motion, off by 12 cm, 6 cm and 1.2 deg.
  const MatchResult result = matcher.MatchExhaustive(pair.scan, {0.0, 0.0, 0.0}, SearchWindow{});
  ASSERT_TRUE(result.converged);
  EXPECT_GT(result.score, 0.9);
  EXPECT_NEAR(result.reference_from_scan.x_m, pair.reference_from_scan.x_m, 0.01);
  EXPECT_NEAR(result.reference_from_scan.y_m, pair.reference_from_scan.y_m, 0.01);
  EXPECT_NEAR(result.reference_from_scan.theta_rad, pair.reference_from_scan.theta_rad, 0.2 * kDeg);
}

TEST(CorrelationScanMatcher, RefinementBeatsTheGridResolution) {
  // True motion between grid poses: the refined pose is much closer than the 6 cm grid.
  const Pair pair = MakePair({1.5, 2.5, 0.0}, {1.53, 2.47, 0.3 * kDeg}, 0.0, 2);
  const CorrelationScanMatcher matcher({}, pair.reference);
  const MatchResult result = matcher.MatchExhaustive(pair.scan, {0.0, 0.0, 0.0}, SearchWindow{});
  EXPECT_NEAR(result.reference_from_scan.x_m, 0.03, 0.005);
  EXPECT_NEAR(result.reference_from_scan.y_m, -0.03, 0.005);
  EXPECT_NEAR(result.reference_from_scan.theta_rad, 0.3 * kDeg, 0.05 * kDeg);
}

TEST(CorrelationScanMatcher, RefineLaterGivesWhatTheSearchWouldHaveRefined) {
  const Pair pair = MakePair({1.5, 2.5, 0.0}, {1.53, 2.47, 0.3 * kDeg}, 0.0, 2);
  const CorrelationScanMatcher matcher({}, pair.reference);
  for (const bool wide : {false, true}) {
    SearchWindow window;
    if (wide) window = {0.8, 0.6, 20.0 * kDeg, 0.06, 0.6 * kDeg};
    auto search = [&](Polish polish) {
      return wide ? matcher.MatchBranchAndBound(pair.scan, {0.1, 0.0, 0.05}, window, polish)
                  : matcher.MatchExhaustive(pair.scan, {0.0, 0.0, 0.0}, window, polish);
    };
    const MatchResult refined = search(Polish::kRefine);
    MatchResult later = search(Polish::kGridPoseOnly);
    EXPECT_DOUBLE_EQ(later.reference_from_scan.x_m, later.grid_pose.x_m);
    EXPECT_TRUE(later.information.isZero());
    matcher.Refine(pair.scan, later);
    EXPECT_DOUBLE_EQ(later.reference_from_scan.x_m, refined.reference_from_scan.x_m);
    EXPECT_DOUBLE_EQ(later.reference_from_scan.y_m, refined.reference_from_scan.y_m);
    EXPECT_DOUBLE_EQ(later.reference_from_scan.theta_rad, refined.reference_from_scan.theta_rad);
    EXPECT_EQ(later.information, refined.information);
    // The refinement moved it, so the comparison above is not of two grid poses.
    EXPECT_GT(std::abs(refined.reference_from_scan.x_m - refined.grid_pose.x_m) +
                  std::abs(refined.reference_from_scan.y_m - refined.grid_pose.y_m) +
                  std::abs(refined.reference_from_scan.theta_rad - refined.grid_pose.theta_rad),
              1e-4)
        << (wide ? "wide" : "paper") << " window";
  }
}

// Branch and bound must return exactly the exhaustive search's grid pose and score. Returns the
// exhaustive search's grid pose.
geometry::Pose2 ExpectSameAsExhaustive(const SearchWindow& window, const geometry::Pose2& prior,
                                       unsigned seed, const CorrelationMatcherOptions& options = {}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(1.0, 7.0), y(1.0, 4.0), theta(-0.6, 0.6);
  const geometry::Pose2 a{x(rng), y(rng), theta(rng)};
  const geometry::Pose2 b{a.x_m + 0.2, a.y_m - 0.1, a.theta_rad + 0.2};
  const Pair pair = MakePair(a, b, 0.01, seed);
  const CorrelationScanMatcher matcher(options, pair.reference);
  const MatchResult exhaustive = matcher.MatchExhaustive(pair.scan, prior, window);
  const MatchResult fast = matcher.MatchBranchAndBound(pair.scan, prior, window);
  EXPECT_EQ(fast.hits, exhaustive.hits);
  EXPECT_EQ(fast.weight, exhaustive.weight);
  EXPECT_DOUBLE_EQ(fast.grid_pose.x_m, exhaustive.grid_pose.x_m);
  EXPECT_DOUBLE_EQ(fast.grid_pose.y_m, exhaustive.grid_pose.y_m);
  EXPECT_DOUBLE_EQ(fast.grid_pose.theta_rad, exhaustive.grid_pose.theta_rad);
  EXPECT_LT(fast.candidates_scored, exhaustive.candidates_scored);
  return exhaustive.grid_pose;
}

TEST(CorrelationScanMatcher, BranchAndBoundAgreesWithExhaustiveOnPaperWindow) {
  for (unsigned seed = 1; seed <= 5; ++seed) ExpectSameAsExhaustive(SearchWindow{}, {0.15, -0.05, 0.19}, seed);
}

TEST(CorrelationScanMatcher, BranchAndBoundAgreesWithExhaustiveOnNoGyroWindow) {
  // The paper's infeasible window without a gyro: 80 cm x 60 cm x 80 deg at 2 cm and 0.5 deg.
  const SearchWindow wide{0.80, 0.60, 80.0 * kDeg, 0.02, 0.5 * kDeg};
  for (unsigned seed = 11; seed <= 13; ++seed) ExpectSameAsExhaustive(wide, {0.0, 0.0, 0.0}, seed);
}

TEST(CorrelationScanMatcher, EmptyScanIsNotConverged) {
  const Pair pair = MakePair({1.5, 2.5, 0.0}, {1.6, 2.5, 0.0}, 0.0, 3);
  const CorrelationScanMatcher matcher({}, pair.reference);
  const MatchResult result = matcher.MatchBranchAndBound({}, {0.0, 0.0, 0.0}, SearchWindow{});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.points, 0);
}

TEST(CorrelationScanMatcher, StepThatIsNotWholeCellsIsRejectedWithFieldName) {
  const CorrelationScanMatcher matcher({}, {{1.0, 0.0}});
  SearchWindow window;
  window.step_xy_m = 0.05;  // 2.5 cells of 2 cm
  EXPECT_THROW(
      {
        try {
          matcher.MatchExhaustive({{1.0, 0.0}}, {}, window);
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find("step_xy_m"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
}

// The paper's window (60 cm x 36 cm x 3 deg at 6 cm / 0.6 deg) has 5 steps each way in x, 3 in
// y and 2.5 in heading: its outermost candidates, and only those, are on the edge.
TEST(CorrelationScanMatcher, OnWindowEdgeMarksOnlyTheOutermostCandidates) {
  const SearchWindow window;  // the paper's
  const geometry::Pose2 prior{2.0, 1.0, 0.5};
  auto at = [&](double dx, double dy, double dtheta) {
    return OnWindowEdge({prior.x_m + dx, prior.y_m + dy, prior.theta_rad + dtheta}, prior, window);
  };
  EXPECT_FALSE(at(0.0, 0.0, 0.0));
  EXPECT_FALSE(at(0.24, 0.12, 0.0));   // 4 and 2 steps out
  EXPECT_TRUE(at(0.30, 0.0, 0.0));     // 5 steps: the last in x
  EXPECT_TRUE(at(-0.30, 0.0, 0.0));
  EXPECT_TRUE(at(0.0, -0.18, 0.0));    // 3 steps: the last in y
  EXPECT_FALSE(at(0.0, 0.0, 0.0105));  // one heading step
  EXPECT_TRUE(at(0.0, 0.0, -0.021));   // two: the last in heading
}

}  // namespace
}  // namespace pena::scan_matching
