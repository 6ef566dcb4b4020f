#include "pena/geometry/pose2.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace pena::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Pose2, NormalizeAngleWrapsIntoHalfOpenRange) {
  EXPECT_NEAR(NormalizeAngle(3.0 * kPi), -kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-kPi / 2 - 4 * kPi), -kPi / 2, 1e-12);
  EXPECT_NEAR(NormalizeAngle(0.25), 0.25, 1e-15);
}

TEST(Pose2, ComposeRotatesTheSecondTranslation) {
  const Pose2 a_from_b{1.0, 2.0, kPi / 2};
  const Pose2 b_from_c{3.0, 0.0, kPi / 2};
  const Pose2 a_from_c = Compose(a_from_b, b_from_c);
  EXPECT_NEAR(a_from_c.x_m, 1.0, 1e-12);
  EXPECT_NEAR(a_from_c.y_m, 5.0, 1e-12);
  EXPECT_NEAR(std::abs(a_from_c.theta_rad), kPi, 1e-12);
}

TEST(Pose2, InverseUndoesCompose) {
  const Pose2 a_from_b{-0.7, 4.2, 2.5};
  const Pose2 identity = Compose(a_from_b, Inverse(a_from_b));
  EXPECT_NEAR(identity.x_m, 0.0, 1e-12);
  EXPECT_NEAR(identity.y_m, 0.0, 1e-12);
  EXPECT_NEAR(identity.theta_rad, 0.0, 1e-12);
}

TEST(Pose2, BetweenGivesMotionInTheFirstPosesFrame) {
  const Pose2 motion = Between({1.0, 1.0, kPi / 2}, {1.0, 3.0, kPi / 2});
  EXPECT_NEAR(motion.x_m, 2.0, 1e-12);  // straight ahead
  EXPECT_NEAR(motion.y_m, 0.0, 1e-12);
  EXPECT_NEAR(motion.theta_rad, 0.0, 1e-12);
}

TEST(Pose2, InterpolateTakesShortestArc) {
  const Pose2 mid = Interpolate({0.0, 0.0, kPi - 0.1}, {2.0, 0.0, -kPi + 0.1}, 0.5);
  EXPECT_NEAR(mid.x_m, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.theta_rad), kPi, 1e-12);
}

}  // namespace
}  // namespace pena::geometry
