#include "pena/eval/trajectory_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "pena/eval/rigid_alignment.hpp"

namespace pena::eval {
namespace {

constexpr double kTol = 1e-9;

// A curving walk, one pose per second: a quarter circle of radius 5 m then a straight leg.
geometry::Trajectory CurvedTruth() {
  geometry::Trajectory truth;
  for (int k = 0; k <= 20; ++k) {
    const double angle_rad = std::numbers::pi / 2 * std::min(k, 10) / 10.0;
    const double straight_m = std::max(0, k - 10) * 0.5;
    truth.push_back(
        {static_cast<double>(k),
         {5.0 * std::sin(angle_rad) - straight_m, 5.0 - 5.0 * std::cos(angle_rad), angle_rad}});
  }
  return truth;
}

geometry::Trajectory Transformed(const geometry::Trajectory& trajectory,
                                 const geometry::Pose2& new_from_old) {
  geometry::Trajectory result = trajectory;
  for (auto& stamped : result) stamped.pose = geometry::Compose(new_from_old, stamped.pose);
  return result;
}

TEST(TrajectoryErrorTest, ConstantOffsetGivesThatOffsetAsRmse) {
  const geometry::Trajectory truth = CurvedTruth();
  geometry::Trajectory estimate = truth;
  for (auto& stamped : estimate) {
    stamped.pose.x_m += 0.3;
    stamped.pose.y_m -= 0.4;
  }
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_EQ(summary.poses_matched, truth.size());
  EXPECT_EQ(summary.poses_skipped, 0u);
  EXPECT_NEAR(summary.translation_rmse_m, 0.5, kTol);
  EXPECT_NEAR(summary.max_translation_error_m, 0.5, kTol);
  EXPECT_NEAR(summary.final_position_error_m, 0.5, kTol);
  EXPECT_NEAR(summary.heading_rmse_deg, 0.0, kTol);
}

TEST(TrajectoryErrorTest, ConstantHeadingOffsetGivesHeadingRmseInDegrees) {
  const geometry::Trajectory truth = CurvedTruth();
  geometry::Trajectory estimate = truth;
  for (auto& stamped : estimate) stamped.pose.theta_rad -= 0.05;
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_NEAR(summary.heading_rmse_deg, 0.05 * 180.0 / std::numbers::pi, kTol);
  EXPECT_NEAR(summary.translation_rmse_m, 0.0, kTol);
  EXPECT_NEAR(summary.max_heading_error_deg, 0.05 * 180.0 / std::numbers::pi, kTol);
  EXPECT_NEAR(summary.final_heading_error_deg, 0.05 * 180.0 / std::numbers::pi, kTol);
}

TEST(TrajectoryErrorTest, FinalHeadingErrorIsTheLastPosesNotTheWorst) {
  const geometry::Trajectory truth = CurvedTruth();
  geometry::Trajectory estimate = truth;
  estimate[5].pose.theta_rad += 0.2;   // a heading jump that is corrected again
  estimate.back().pose.theta_rad -= 0.03;
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_NEAR(summary.max_heading_error_deg, 0.2 * 180.0 / std::numbers::pi, kTol);
  EXPECT_NEAR(summary.final_heading_error_deg, 0.03 * 180.0 / std::numbers::pi, kTol);
}

TEST(TrajectoryErrorTest, AlignmentRemovesRigidTransformExactly) {
  const geometry::Trajectory truth = CurvedTruth();
  const geometry::Pose2 estimate_from_truth{5.0, -2.0, 0.7};
  const geometry::Trajectory estimate = Transformed(truth, estimate_from_truth);

  const TrajectoryErrorSummary unaligned = EvaluateAgainstTruth(estimate, truth);
  EXPECT_GT(unaligned.translation_rmse_m, 1.0);
  EXPECT_NEAR(unaligned.heading_rmse_deg, 0.7 * 180.0 / std::numbers::pi, 1e-6);

  const TrajectoryErrorSummary aligned = EvaluateAgainstTruth(estimate, truth, {.align = true});
  EXPECT_NEAR(aligned.translation_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(aligned.heading_rmse_deg, 0.0, 1e-7);
  const geometry::Pose2 expected = geometry::Inverse(estimate_from_truth);
  EXPECT_NEAR(aligned.truth_from_estimate.x_m, expected.x_m, 1e-9);
  EXPECT_NEAR(aligned.truth_from_estimate.y_m, expected.y_m, 1e-9);
  EXPECT_NEAR(aligned.truth_from_estimate.theta_rad, expected.theta_rad, 1e-12);
}

TEST(TrajectoryErrorTest, AlignmentIsLeastSquaresUnderNoise) {
  // Symmetric +-0.1 m noise on x only about a known transform: the fit must not absorb it fully,
  // and the residual RMSE cannot exceed the noise.
  const geometry::Trajectory truth = CurvedTruth();
  geometry::Trajectory estimate = Transformed(truth, {1.0, 2.0, -0.3});
  for (std::size_t k = 0; k < estimate.size(); ++k) estimate[k].pose.x_m += k % 2 ? 0.1 : -0.1;
  const TrajectoryErrorSummary aligned = EvaluateAgainstTruth(estimate, truth, {.align = true});
  EXPECT_LE(aligned.translation_rmse_m, 0.1 + 1e-9);
  EXPECT_GT(aligned.translation_rmse_m, 0.05);
}

TEST(RigidAlignmentTest, RejectsTooFewOrUnmatchedPoints) {
  EXPECT_THROW(AlignRigid2D({Eigen::Vector2d(0, 0)}, {Eigen::Vector2d(1, 1)}),
               std::invalid_argument);
  EXPECT_THROW(
      AlignRigid2D({Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)}, {Eigen::Vector2d(1, 1)}),
      std::invalid_argument);
}

TEST(TrajectoryErrorTest, FinalErrorIsPercentOfTruthPathLength) {
  // Truth walks 10 m along x in 1 m steps; the estimate ends 0.2 m to the side: 2 % of the path.
  geometry::Trajectory truth;
  for (int k = 0; k <= 10; ++k) truth.push_back({k * 1.0, {k * 1.0, 0.0, 0.0}});
  geometry::Trajectory estimate = truth;
  estimate.back().pose.y_m = 0.2;
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_NEAR(summary.truth_path_length_m, 10.0, kTol);
  EXPECT_NEAR(summary.final_position_error_m, 0.2, kTol);
  EXPECT_NEAR(summary.final_error_percent_of_path, 2.0, kTol);
}

TEST(TrajectoryErrorTest, PathLengthFollowsEveryTruthSampleBetweenSparseMatches) {
  // Truth zigzags (each step 1 m along x and +-1 m along y); the estimate has only the ends.
  geometry::Trajectory truth;
  for (int k = 0; k <= 4; ++k) truth.push_back({k * 1.0, {k * 1.0, k % 2 ? 1.0 : 0.0, 0.0}});
  const geometry::Trajectory estimate = {{0.0, {0.0, 0.0, 0.0}}, {4.0, {4.0, 0.5, 0.0}}};
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_EQ(summary.poses_matched, 2u);
  EXPECT_NEAR(summary.truth_path_length_m, 4.0 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(summary.final_error_percent_of_path, 100.0 * 0.5 / (4.0 * std::sqrt(2.0)), kTol);
}

TEST(TrajectoryErrorTest, SkipsAndCountsEstimatedPosesWithoutTruth) {
  const geometry::Trajectory truth = {{0.0, {}}, {1.0, {}}, {2.0, {}}};
  const geometry::Trajectory estimate = {
      {0.0, {}}, {0.5, {9.0, 9.0, 0.0}}, {1.0002, {0.1, 0.0, 0.0}}, {3.0, {}}};
  const TrajectoryErrorSummary summary = EvaluateAgainstTruth(estimate, truth);
  EXPECT_EQ(summary.poses_matched, 2u);
  EXPECT_EQ(summary.poses_skipped, 2u);
  EXPECT_NEAR(summary.translation_rmse_m, std::sqrt(0.01 / 2.0), kTol);
  EXPECT_NEAR(summary.max_translation_error_m, 0.1, kTol);
}

TEST(TrajectoryErrorTest, RejectsUnusableInput) {
  const geometry::Trajectory truth = CurvedTruth();
  EXPECT_THROW(EvaluateAgainstTruth({}, truth), std::invalid_argument);
  EXPECT_THROW(EvaluateAgainstTruth(truth, {}), std::invalid_argument);
  EXPECT_THROW(EvaluateAgainstTruth({{2.0, {}}, {1.0, {}}}, truth), std::invalid_argument);
  EXPECT_THROW(EvaluateAgainstTruth({{100.5, {}}}, truth), std::invalid_argument);
  // One matched pose cannot fix a rotation.
  EXPECT_THROW(EvaluateAgainstTruth({{1.0, {}}}, truth, {.align = true}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::eval
