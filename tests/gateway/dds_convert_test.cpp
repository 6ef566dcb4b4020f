// The gateway's DDS conversions of poses (gateway/dds_convert.hpp): what of the covariance
// crosses the link. Conversions only; no participant.
#include "pena/gateway/dds_convert.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pena::gateway {
namespace {

pena_dds::EntityPose SampleWithCovariance(const std::array<double, 9>& covariance) {
  pena_dds::EntityPose sample;
  sample.entity_id("ff1");
  sample.world_from_body().x_m(3.0);
  sample.covariance(covariance);
  return sample;
}

TEST(GatewayDdsConvert, PoseCarriesTheLargestAxisOfItsCovariance) {
  // An ellipse 0.2 m along x, 0.1 m along y; heading 0.02 rad.
  PoseUpdate pose =
      PoseFromDds(SampleWithCovariance({0.04, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.0004}), 5.0);
  EXPECT_EQ(pose.entity, "ff1");
  EXPECT_DOUBLE_EQ(pose.world_from_body.x_m, 3.0);
  EXPECT_NEAR(pose.position_sd_m, 0.2, 1e-12);
  EXPECT_NEAR(pose.heading_sd_rad, 0.02, 1e-12);
  // Correlated: the largest axis lies along the diagonal, variance 0.02 + 0.01.
  pose = PoseFromDds(SampleWithCovariance({0.02, 0.01, 0.0, 0.01, 0.02, 0.0, 0.0, 0.0, 0.0}), 5.0);
  EXPECT_NEAR(pose.position_sd_m, std::sqrt(0.03), 1e-12);
  EXPECT_EQ(pose.heading_sd_rad, 0.0);
}

TEST(GatewayDdsConvert, MalformedCovarianceIsUnknownNotCertain) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PoseUpdate pose =
      PoseFromDds(SampleWithCovariance({nan, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.01}), 5.0);
  EXPECT_EQ(pose.position_sd_m, 0.0);
  EXPECT_EQ(pose.heading_sd_rad, 0.0);
  pose = PoseFromDds(SampleWithCovariance({-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0}), 5.0);
  EXPECT_EQ(pose.position_sd_m, 0.0);
  EXPECT_EQ(pose.heading_sd_rad, 0.0);
  EXPECT_EQ(PoseFromDds(SampleWithCovariance({}), 5.0).position_sd_m, 0.0);  // none sent
}

TEST(GatewayDdsConvert, FarSidePoseHasACircularCovariance) {
  const PoseUpdate pose{"ff1", {1.0, 2.0, 0.5}, 7.0, 0.3, 0.02};
  const pena_dds::EntityPose sample = PoseToDds(pose, 4);
  const std::array<double, 9>& covariance = sample.covariance();
  EXPECT_NEAR(covariance[0], 0.09, 1e-12);
  EXPECT_NEAR(covariance[4], 0.09, 1e-12);
  EXPECT_NEAR(covariance[8], 0.0004, 1e-12);
  for (int i : {1, 2, 3, 5, 6, 7}) EXPECT_EQ(covariance[static_cast<std::size_t>(i)], 0.0) << i;
  // And back: the same sigmas.
  const PoseUpdate back = PoseFromDds(sample, 7.0);
  EXPECT_NEAR(back.position_sd_m, 0.3, 1e-12);
  EXPECT_NEAR(back.heading_sd_rad, 0.02, 1e-12);
}

// An operator's correction and pena-fusion's answer cross whole; NaN is refused, not carried.
TEST(GatewayDdsConvert, OperatorCorrectionRoundTripsAndRefusesNaN) {
  pena_dds::OperatorCorrection sample;
  sample.correction_id("post/12");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  sample.operator_id("post");
  sample.kind(pena_dds::OPERATOR_TRANSLATE);
  sample.target_entity_id("ff3");
  sample.stamp_s(17.25);
  sample.wrong_point().x_m(1.0);
  sample.correct_point().y_m(-2.0);
  sample.seq(12);
  sample.applied(true);
  std::string error;
  const std::optional<OperatorCorrection> link = OperatorCorrectionFromDds(sample, 99.0, &error);
  ASSERT_TRUE(link) << error;
  EXPECT_EQ(link->stamp_s, 99.0);
  const pena_dds::OperatorCorrection back = OperatorCorrectionToDds(*link);
  EXPECT_EQ(back.correction_id().to_string(), "post/12");
  EXPECT_EQ(back.operator_id().to_string(), "post");
  EXPECT_EQ(back.kind(), pena_dds::OPERATOR_TRANSLATE);
  EXPECT_EQ(back.target_entity_id().to_string(), "ff3");
  EXPECT_EQ(back.stamp_s(), 17.25);
  EXPECT_EQ(back.wrong_point().x_m(), 1.0);
  EXPECT_EQ(back.correct_point().y_m(), -2.0);
  EXPECT_EQ(back.seq(), 12U);
  EXPECT_TRUE(back.applied());
  sample.correct_point().x_m(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(OperatorCorrectionFromDds(sample, 99.0, &error));
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
}

// Far-side poses and marks carry the mission time, not the link's wall clock.
TEST(GatewayDdsConvert, MissionTimeCrossesOnPosesAndMarks) {
  pena_dds::EntityPose pose = SampleWithCovariance({});
  pose.stamp_s(42.5);
  PoseUpdate update = PoseFromDds(pose, 1.7e9);
  ASSERT_TRUE(update.mission_stamp_s);
  EXPECT_EQ(PoseToDds(update, 1).stamp_s(), 42.5);
  update.mission_stamp_s.reset();
  EXPECT_EQ(PoseToDds(update, 1).stamp_s(), 1.7e9);  // unknown: the wall clock, as before

  pena_dds::Annotation mark;
  mark.annotation_id("post/3");
  mark.author_id("post");
  mark.kind(pena_dds::ANNOTATION_DANGEROUS_AREA);
  mark.stamp_s(42.5);
  pena_dds::Point2 corner;
  for (double x : {0.0, 4.0, 4.0}) {
    corner.x_m(x);
    corner.y_m(x > 0 ? 3.0 : 0.0);
    mark.outline().push_back(corner);
  }
  std::string error;
  const std::optional<Annotation> link = AnnotationFromDds(mark, 1.7e9, &error);
  ASSERT_TRUE(link) << error;
  const pena_dds::Annotation back = AnnotationToDds(*link);
  EXPECT_EQ(back.stamp_s(), 42.5);
  ASSERT_EQ(back.outline().size(), 3U);
  EXPECT_EQ(back.outline()[1].x_m(), 4.0);
}

}  // namespace
}  // namespace pena::gateway
