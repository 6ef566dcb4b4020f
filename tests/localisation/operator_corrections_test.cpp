#include "pena/localisation/operator_corrections.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace pena::localisation {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;

geometry::Trajectory Straight() {
  // Walking east along y = 1: (0,1), (1,1), (2,1), (3,1) at t = 0..3.
  geometry::Trajectory t;
  for (int i = 0; i < 4; ++i) t.push_back({static_cast<double>(i), {static_cast<double>(i), 1.0, 0.0}});
  return t;
}

void ExpectTrajectory(const geometry::Trajectory& got, const geometry::Trajectory& expected) {
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].stamp_s, expected[i].stamp_s);
    EXPECT_NEAR(got[i].pose.x_m, expected[i].pose.x_m, 1e-12) << "pose " << i;
    EXPECT_NEAR(got[i].pose.y_m, expected[i].pose.y_m, 1e-12) << "pose " << i;
    EXPECT_NEAR(geometry::NormalizeAngle(got[i].pose.theta_rad - expected[i].pose.theta_rad), 0.0, 1e-12)
        << "pose " << i;
  }
}

TEST(OperatorCorrections, RotatesAboutTheOriginFromTheChosenTime) {
  // Heading lost at (1, 1): the path should have turned north. Origin (1,1), wrong (3,1), correct (1,3).
  OperatorCorrections corrections;
  corrections.Add(RotationCorrection{1.0, {1.0, 1.0}, {3.0, 1.0}, {1.0, 3.0}});
  ExpectTrajectory(corrections.Apply(Straight()), {{0.0, {0.0, 1.0, 0.0}},
                                                   {1.0, {1.0, 1.0, kHalfPi}},
                                                   {2.0, {1.0, 2.0, kHalfPi}},
                                                   {3.0, {1.0, 3.0, kHalfPi}}});
}

TEST(OperatorCorrections, TranslatesFromTheChosenTime) {
  OperatorCorrections corrections;
  corrections.Add(TranslationCorrection{2.0, {2.0, 1.0}, {2.5, 0.0}});
  ExpectTrajectory(corrections.Apply(Straight()), {{0.0, {0.0, 1.0, 0.0}},
                                                   {1.0, {1.0, 1.0, 0.0}},
                                                   {2.0, {2.5, 0.0, 0.0}},
                                                   {3.0, {3.5, 0.0, 0.0}}});
}

TEST(OperatorCorrections, ComposesInOrderAndUndoes) {
  OperatorCorrections corrections;
  corrections.Add(RotationCorrection{1.0, {1.0, 1.0}, {3.0, 1.0}, {1.0, 3.0}});
  // Given on the rotated path (as the operator sees it): the pose at t = 2, now (1, 2), belongs
  // at (0, 2); t = 3 follows it.
  corrections.Add(TranslationCorrection{2.0, {1.0, 2.0}, {0.0, 2.0}});
  const geometry::Trajectory both = {{0.0, {0.0, 1.0, 0.0}},
                                     {1.0, {1.0, 1.0, kHalfPi}},
                                     {2.0, {0.0, 2.0, kHalfPi}},
                                     {3.0, {0.0, 3.0, kHalfPi}}};
  ExpectTrajectory(corrections.Apply(Straight()), both);
  // The per-stamp transform agrees with Apply.
  for (const geometry::StampedPose2& raw : Straight()) {
    const geometry::Pose2 p = geometry::Compose(corrections.CorrectedFromRaw(raw.stamp_s), raw.pose);
    const auto& e = both[static_cast<std::size_t>(raw.stamp_s)].pose;
    EXPECT_NEAR(p.x_m, e.x_m, 1e-12);
    EXPECT_NEAR(p.y_m, e.y_m, 1e-12);
    EXPECT_NEAR(geometry::NormalizeAngle(p.theta_rad - e.theta_rad), 0.0, 1e-12);
  }
  ASSERT_TRUE(corrections.Undo());
  ExpectTrajectory(corrections.Apply(Straight()), {{0.0, {0.0, 1.0, 0.0}},
                                                   {1.0, {1.0, 1.0, kHalfPi}},
                                                   {2.0, {1.0, 2.0, kHalfPi}},
                                                   {3.0, {1.0, 3.0, kHalfPi}}});
  ASSERT_TRUE(corrections.Undo());
  ExpectTrajectory(corrections.Apply(Straight()), Straight());
  EXPECT_FALSE(corrections.Undo());
}

TEST(OperatorCorrections, RejectsARotationWithoutADirection) {
  OperatorCorrections corrections;
  EXPECT_THROW(corrections.Add(RotationCorrection{0.0, {1.0, 1.0}, {1.0, 1.0}, {2.0, 2.0}}),
               std::invalid_argument);
  EXPECT_EQ(corrections.size(), 0u);
}

}  // namespace
}  // namespace pena::localisation
