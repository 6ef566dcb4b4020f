#include "pena/eval/relation_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pena::eval {
namespace {

constexpr double kTol = 1e-9;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

TEST(RelationErrorTest, MeasuresPureTranslationErrorInTheBodyFrame) {
  // The body faces +y: moving 1.5 m along +y is 1.5 m forward, the relation says 1 m forward.
  const geometry::Trajectory estimate = {{0.0, {2.0, 3.0, std::numbers::pi / 2}},
                                         {1.0, {2.0, 4.5, std::numbers::pi / 2}}};
  const RelationErrorSummary summary = EvaluateRelations(estimate, {{0.0, 1.0, {1.0, 0.0, 0.0}}});
  ASSERT_EQ(summary.relations_used, 1u);
  EXPECT_NEAR(summary.translation_m.mean, 0.5, kTol);
  EXPECT_NEAR(summary.translation_sq_m2.mean, 0.25, kTol);
  EXPECT_NEAR(summary.rotation_deg.mean, 0.0, kTol);
}

TEST(RelationErrorTest, MeasuresPureRotationErrorInDegrees) {
  const geometry::Trajectory estimate = {{0.0, {0.0, 0.0, 0.0}}, {1.0, {1.0, 0.0, 0.1}}};
  const RelationErrorSummary summary = EvaluateRelations(estimate, {{0.0, 1.0, {1.0, 0.0, 0.0}}});
  EXPECT_NEAR(summary.translation_m.mean, 0.0, kTol);
  EXPECT_NEAR(summary.rotation_deg.mean, 0.1 * kDegPerRad, kTol);
  EXPECT_NEAR(summary.rotation_sq_deg2.mean, std::pow(0.1 * kDegPerRad, 2), 1e-7);
}

TEST(RelationErrorTest, WrapsRotationErrorAcrossPi) {
  // Estimated turn +3.1 rad, true turn -3.1 rad: they differ by 2 pi - 6.2 rad, not 6.2 rad.
  const RelationError error =
      ComputeRelationError({0.0, 1.0, {0.0, 0.0, -3.1}}, {0.0, 0.0, 0.0}, {0.0, 0.0, 3.1});
  EXPECT_NEAR(error.rotation_error_rad, 2.0 * std::numbers::pi - 6.2, kTol);
}

TEST(RelationErrorTest, SeparatesTranslationAndRotationOfOneRelation) {
  // relation^-1 * estimate = (-1, -0.1, 0) * (1, 0, 0.2) = (0, -0.1, 0.2).
  const RelationError error =
      ComputeRelationError({0.0, 1.0, {1.0, 0.1, 0.0}}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.2});
  EXPECT_NEAR(error.translation_error_m, 0.1, kTol);
  EXPECT_NEAR(error.rotation_error_rad, 0.2, kTol);
}

TEST(RelationErrorTest, TranslationErrorIsTheDistanceBetweenTranslations) {
  // With a turning relation the error lives in the frame of the relation's end, yet its length is
  // |t_est - t_rel|: here |(2, 1) - (2, 0)| = 1.
  const RelationError error =
      ComputeRelationError({0.0, 1.0, {2.0, 0.0, 1.0}}, {0.0, 0.0, 0.0}, {2.0, 1.0, 1.0});
  EXPECT_NEAR(error.translation_error_m, 1.0, kTol);
  EXPECT_NEAR(error.rotation_error_rad, 0.0, kTol);
}

TEST(RelationErrorTest, SummarisesMeanAndStdOfErrorsAndSquares) {
  const geometry::Trajectory estimate = {
      {0.0, {0.0, 0.0, 0.0}}, {1.0, {1.3, 0.0, 0.0}}, {2.0, {2.3, 0.0, 0.0}}};
  const double two_deg_rad = 2.0 / kDegPerRad;
  const std::vector<geometry::Relation> relations = {
      {0.0, 1.0, {1.0, 0.0, 0.0}},           // 0.3 m, 0 deg
      {1.0, 2.0, {0.9, 0.0, -two_deg_rad}},  // 0.1 m, 2 deg
  };
  const RelationErrorSummary summary = EvaluateRelations(estimate, relations);
  ASSERT_EQ(summary.relations_used, 2u);
  EXPECT_NEAR(summary.translation_m.mean, 0.2, kTol);
  EXPECT_NEAR(summary.translation_m.std, 0.1, kTol);
  EXPECT_NEAR(summary.translation_sq_m2.mean, 0.05, kTol);  // (0.09 + 0.01) / 2
  EXPECT_NEAR(summary.translation_sq_m2.std, 0.04, kTol);
  EXPECT_NEAR(summary.rotation_deg.mean, 1.0, kTol);
  EXPECT_NEAR(summary.rotation_deg.std, 1.0, kTol);
  EXPECT_NEAR(summary.rotation_sq_deg2.mean, 2.0, 1e-7);  // (0 + 4) / 2
  EXPECT_NEAR(summary.rotation_sq_deg2.std, 2.0, 1e-7);
  EXPECT_NEAR(summary.translation_spread_m.median, 0.1, kTol);
  EXPECT_NEAR(summary.translation_spread_m.max, 0.3, kTol);
  EXPECT_NEAR(summary.rotation_spread_deg.max, 2.0, 1e-7);
}

TEST(RelationErrorTest, SkipsAndCountsRelationsWithStampsNotInTrajectory) {
  const geometry::Trajectory estimate = {
      {0.0, {0.0, 0.0, 0.0}}, {1.0, {1.0, 0.0, 0.0}}, {2.0, {2.0, 0.0, 0.0}}};
  const std::vector<geometry::Relation> relations = {
      {0.0, 1.0, {1.0, 0.0, 0.0}},     // exact
      {1.0, 1.5, {0.5, 0.0, 0.0}},     // 1.5 s has no pose
      {1.0005, 2.0, {1.0, 0.0, 0.0}},  // 0.5 ms off: the same instant
      {2.0, 3.0, {1.0, 0.0, 0.0}},     // after the end
  };
  const RelationErrorSummary summary = EvaluateRelations(estimate, relations);
  EXPECT_EQ(summary.relations_used, 2u);
  EXPECT_EQ(summary.relations_skipped, 2u);
  ASSERT_EQ(summary.errors.size(), 2u);
  EXPECT_DOUBLE_EQ(summary.errors[1].t1_s, 1.0005);
  EXPECT_NEAR(summary.translation_m.mean, 0.0, kTol);
}

TEST(RelationErrorTest, RejectsUnusableInput) {
  const geometry::Trajectory estimate = {{0.0, {}}, {1.0, {}}};
  EXPECT_THROW(EvaluateRelations({}, {{0.0, 1.0, {}}}), std::invalid_argument);
  EXPECT_THROW(EvaluateRelations(estimate, {}), std::invalid_argument);
  EXPECT_THROW(EvaluateRelations({{1.0, {}}, {0.0, {}}}, {{0.0, 1.0, {}}}), std::invalid_argument);
  EXPECT_THROW(EvaluateRelations(estimate, {{5.0, 6.0, {}}}), std::invalid_argument);
  EXPECT_THROW(EvaluateRelations(estimate, {{0.0, 1.0, {}}}, {.stamp_tolerance_s = -1.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace pena::eval
