// Gating and blending of virtual-scan corrections with the entity's pose uncertainty.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pena/fusion/correction_filter.hpp"
#include "pena/localisation/virtual_scanner.hpp"

namespace pena::fusion {
namespace {

geometry::Segment2 S(double x1, double y1, double x2, double y2) {
  return geometry::Segment2{{x1, y1}, {x2, y2}};
}

// A 60 m featureless corridor along x, 2 m wide: nothing fixes x.
std::vector<geometry::Segment2> Corridor() { return {S(-30, 0, 30, 0), S(-30, 2, 30, 2)}; }

// An L-shaped corridor with a side room: enough structure to fix x, y and heading.
std::vector<geometry::Segment2> Building() {
  return {S(0, 0, 20, 0), S(0, 2, 8, 2), S(10, 2, 18, 2), S(18, 2, 18, 12), S(20, 0, 20, 12),
          S(8, 2, 8, 6),  S(10, 2, 10, 6), S(8, 6, 10, 6), S(0, 0, 0, 2)};
}

sensors::LaserScan ScanOf(const std::vector<geometry::Segment2>& walls,
                          const geometry::Pose2& map_from_body) {
  const localisation::VirtualScanner truth(walls);
  sensors::LaserGeometry laser{-std::numbers::pi / 2.0, std::numbers::pi / 360.0, 30.0};
  return truth.Scan(map_from_body, laser, 361, 12.0);
}

// A filter whose prediction is `sd_m` uncertain (walked `metres` at 0.1 m/sqrt(m)).
CorrectionFilter Drifted(double metres) {
  CorrectionFilterOptions options;
  options.translation_noise_m_per_sqrt_m = 0.1;
  CorrectionFilter filter(options);
  filter.Predict({0, 0, 0});
  filter.Predict({metres, 0, 0});
  return filter;
}

TEST(CorrectionFilter, NeverMovesAnEntityAlongADegenerateCorridor) {
  const geometry::Pose2 truth{0.0, 1.0, 0.0};
  // The prediction is 0.4 m ahead along the corridor and 0.2 m off across it.
  const geometry::Pose2 predicted{0.4, 1.2, 0.0};
  CorrectionFilter filter = Drifted(50.0);
  const FusionCorrection match =
      ComputeCorrection("ff1", ScanOf(Corridor(), truth), predicted, {}, Corridor());
  ASSERT_TRUE(match.accepted) << match.reason;
  const FilteredCorrection out = filter.Update(predicted, match);
  ASSERT_TRUE(out.accepted) << out.reason;
  EXPECT_TRUE(out.degenerate);
  EXPECT_NEAR(out.map_from_body.x_m, predicted.x_m, 0.01);  // the axis is left alone
  EXPECT_NEAR(out.map_from_body.y_m, truth.y_m, 0.05);      // across it is corrected
}

TEST(CorrectionFilter, BlendsByUncertaintyInsteadOfJumping) {
  // Near the corner, looking up the north corridor: x, y and heading are all constrained.
  const geometry::Pose2 truth{17.0, 1.0, 0.8};
  const geometry::Pose2 predicted{17.2, 1.15, 0.8};
  const sensors::LaserScan scan = ScanOf(Building(), truth);
  const FusionCorrection match = ComputeCorrection("ff1", scan, predicted, {}, Building());
  ASSERT_TRUE(match.accepted) << match.reason;
  // A drifted entity (50 m walked, sd 0.7 m) takes nearly all of the correction ...
  CorrectionFilter drifted = Drifted(50.0);
  const FilteredCorrection large = drifted.Update(predicted, match);
  ASSERT_TRUE(large.accepted) << large.reason;
  EXPECT_FALSE(large.degenerate);
  EXPECT_NEAR(large.map_from_body.x_m, truth.x_m, 0.03);
  EXPECT_NEAR(large.map_from_body.y_m, truth.y_m, 0.03);
  EXPECT_LT(large.covariance(0, 0), 0.02);
  // ... one with good odometry (1 m walked, sd 0.1 m) moves only part of the way.
  CorrectionFilter good = Drifted(1.0);
  const FilteredCorrection small = good.Update(predicted, match);
  ASSERT_TRUE(small.accepted) << small.reason;
  const double moved = std::hypot(small.map_from_body.x_m - predicted.x_m,
                                  small.map_from_body.y_m - predicted.y_m);
  EXPECT_GT(moved, 0.05);
  EXPECT_LT(moved, 0.6 * std::hypot(0.2, 0.15));
}

TEST(CorrectionFilter, RefusesAnInnovationFarOutsideTheUncertainty) {
  const geometry::Pose2 truth{17.0, 1.0, 0.8};
  const geometry::Pose2 predicted{17.45, 1.0, 0.8};
  const FusionCorrection match =
      ComputeCorrection("robot1", ScanOf(Building(), truth), predicted, {}, Building());
  ASSERT_TRUE(match.accepted) << match.reason;
  CorrectionFilterOptions options;
  options.translation_noise_m_per_sqrt_m = 0.01;  // a robot: 2 m walked, sd 0.05 m
  options.map_sd_m = 0.05;
  options.min_update_sd_m = 0.0;
  CorrectionFilter filter(options);
  filter.Predict({0, 0, 0});
  filter.Predict({2, 0, 0});
  const Eigen::Matrix3d before = filter.covariance();
  const FilteredCorrection out = filter.Update(predicted, match);
  EXPECT_FALSE(out.accepted);
  EXPECT_GT(out.mahalanobis_sq, options.gate_mahalanobis_sq);
  EXPECT_EQ(out.map_from_body.x_m, predicted.x_m);
  // The prediction may have jumped: the next window is wider.
  EXPECT_TRUE(filter.covariance().isApprox(options.refused_growth * before));
}

TEST(CorrectionFilter, LeavesAPredictionMorePreciseThanTheMapAlone) {
  const geometry::Pose2 truth{17.0, 1.0, 0.8};
  const geometry::Pose2 predicted{17.1, 1.05, 0.8};
  const FusionCorrection match =
      ComputeCorrection("robot1", ScanOf(Building(), truth), predicted, {}, Building());
  ASSERT_TRUE(match.accepted) << match.reason;
  CorrectionFilterOptions options;
  options.initial_sd_m = 0.02;  // a robot at its known start
  CorrectionFilter filter(options);
  const FilteredCorrection out = filter.Update(predicted, match);
  EXPECT_FALSE(out.accepted);
  EXPECT_EQ(out.map_from_body.x_m, predicted.x_m);
}

TEST(CorrectionFilter, WindowFollowsTheUncertainty) {
  const scan_matching::SearchWindow widest = CorrectionOptions{}.window;
  const scan_matching::SearchWindow narrow = Drifted(0.0).Window(widest);
  EXPECT_NEAR(narrow.size_x_m, CorrectionFilterOptions{}.min_window_m, 1e-9);
  const scan_matching::SearchWindow wide = Drifted(100.0).Window(widest);
  EXPECT_NEAR(wide.size_x_m, widest.size_x_m, 1e-9);
  EXPECT_THROW(CorrectionFilter(CorrectionFilterOptions{.map_sd_m = 0.0}), std::invalid_argument);
}

TEST(CorrectionFilter, TakesTheEntitysOwnCovarianceGrowthWhereItExceedsTheModel) {
  // The model says 0.005 m/sqrt(m) and 0.0005 rad/sqrt(m) (a simulated robot); the entity's
  // odometry reports its heading variance grew by 0.01 rad^2 over the same 4 m.
  CorrectionFilterOptions options;
  options.translation_noise_m_per_sqrt_m = 0.005;
  options.heading_noise_rad_per_sqrt_m = 0.0005;
  options.turn_noise_rad_per_sqrt_rad = 0.0;
  CorrectionFilter model(options), reported(options);
  const Eigen::Matrix3d before = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
  const Eigen::Matrix3d after = Eigen::Vector3d(1e-4, 1e-4, 1e-4 + 0.01).asDiagonal();
  model.Predict({0, 0, 0});
  model.Predict({4, 0, 0});
  reported.Predict({0, 0, 0}, before);
  reported.Predict({4, 0, 0}, after);
  EXPECT_NEAR(reported.covariance()(2, 2) - model.covariance()(2, 2),
              0.01 - 4 * 0.0005 * 0.0005, 1e-9);
  // Its position grew less than the model says: the model's growth stays.
  EXPECT_NEAR(reported.covariance()(0, 0), model.covariance()(0, 0), 1e-12);
  // A covariance that shrank (the entity applied a correction) adds nothing beyond the model.
  CorrectionFilter corrected(options);
  corrected.Predict({0, 0, 0}, after);
  corrected.Predict({4, 0, 0}, before);
  EXPECT_NEAR(corrected.covariance()(2, 2), model.covariance()(2, 2), 1e-12);
}

TEST(CorrectionFilter, ScalesItsNoiseUpWhenMatchesKeepDisagreeingAndNotForOne) {
  // Near the corner of the building every match is good. The prediction is 0.3 m off each time
  // while the filter believes 0.06 m: after adapt_window matches it has learnt its noise is
  // larger; one such match among consistent ones teaches nothing.
  const geometry::Pose2 truth{17.0, 1.0, 0.8};
  const geometry::Pose2 off{17.3, 1.0, 0.8};
  CorrectionFilterOptions options;
  options.translation_noise_m_per_sqrt_m = 0.02;
  options.adapt_window = 4;
  const FusionCorrection match =
      ComputeCorrection("ff1", ScanOf(Building(), truth), off, {}, Building());
  ASSERT_TRUE(match.accepted) << match.reason;
  const FusionCorrection agreeing =
      ComputeCorrection("ff1", ScanOf(Building(), truth), truth, {}, Building());
  ASSERT_TRUE(agreeing.accepted) << agreeing.reason;
  CorrectionFilter drifting(options), steady(options);
  for (int i = 0; i < 4; ++i) {
    drifting.Predict({0, 0, 0});
    drifting.Predict({9, 0, 0});
    drifting.Update(off, match);
    steady.Predict({0, 0, 0});
    steady.Predict({9, 0, 0});
    steady.Update(i == 0 ? off : truth, i == 0 ? match : agreeing);
  }
  EXPECT_GT(drifting.noise_scale(), 1.5);
  EXPECT_DOUBLE_EQ(steady.noise_scale(), 1.0);
  options.adapt_window = 0;
  CorrectionFilter fixed(options);
  for (int i = 0; i < 4; ++i) {
    fixed.Predict({0, 0, 0});
    fixed.Predict({9, 0, 0});
    fixed.Update(off, match);
  }
  EXPECT_DOUBLE_EQ(fixed.noise_scale(), 1.0);
}

}  // namespace
}  // namespace pena::fusion
