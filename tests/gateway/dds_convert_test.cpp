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

}  // namespace
}  // namespace pena::gateway
