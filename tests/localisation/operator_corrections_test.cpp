#include "pena/localisation/operator_corrections.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace pena::localisation {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;

void ExpectPose(const geometry::Pose2& got, const geometry::Pose2& expected) {
  EXPECT_NEAR(got.x_m, expected.x_m, 1e-12);
  EXPECT_NEAR(got.y_m, expected.y_m, 1e-12);
  EXPECT_NEAR(geometry::NormalizeAngle(got.theta_rad - expected.theta_rad), 0.0, 1e-12);
}

TEST(OperatorCorrections, RotatesAboutTheOrigin) {
  // Walking east along y = 1, the heading was lost at (1, 1): the path should have turned north.
  // Origin (1,1), wrong (3,1), correct (1,3).
  const OperatorCorrection rotation = RotationCorrection{1.0, {1.0, 1.0}, {3.0, 1.0}, {1.0, 3.0}};
  const geometry::Pose2 corrected_from_wrong = CorrectionTransform(rotation);
  ExpectPose(geometry::Compose(corrected_from_wrong, {1.0, 1.0, 0.0}), {1.0, 1.0, kHalfPi});
  ExpectPose(geometry::Compose(corrected_from_wrong, {3.0, 1.0, 0.0}), {1.0, 3.0, kHalfPi});
  EXPECT_EQ(FromStamp(rotation), 1.0);
}

TEST(OperatorCorrections, TranslatesThePointToItsCorrectPosition) {
  const OperatorCorrection translation = TranslationCorrection{2.0, {2.0, 1.0}, {2.5, 0.0}};
  const geometry::Pose2 corrected_from_wrong = CorrectionTransform(translation);
  ExpectPose(geometry::Compose(corrected_from_wrong, {2.0, 1.0, 0.3}), {2.5, 0.0, 0.3});
  ExpectPose(geometry::Compose(corrected_from_wrong, {3.0, 1.0, 0.0}), {3.5, 0.0, 0.0});
  EXPECT_EQ(FromStamp(translation), 2.0);
}

TEST(OperatorCorrections, RejectsARotationWithoutADirection) {
  EXPECT_THROW(CorrectionTransform(RotationCorrection{0.0, {1.0, 1.0}, {1.0, 1.0}, {2.0, 2.0}}),
               std::invalid_argument);
  EXPECT_THROW(CorrectionTransform(RotationCorrection{0.0, {1.0, 1.0}, {2.0, 2.0}, {1.0, 1.0}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
