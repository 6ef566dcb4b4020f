#include "pena/eval/stamp_matching.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace pena::eval {
namespace {

geometry::Trajectory ThreePoses() { return {{10.0, {}}, {10.1, {}}, {10.2, {}}}; }

TEST(StampMatchingTest, FindsClosestStampWithinTolerance) {
  const geometry::Trajectory trajectory = ThreePoses();
  EXPECT_EQ(FindStamp(trajectory, 10.1), 1u);
  EXPECT_EQ(FindStamp(trajectory, 10.1004), 1u);
  EXPECT_EQ(FindStamp(trajectory, 10.0996), 1u);
  EXPECT_EQ(FindStamp(trajectory, 10.2), 2u);
  EXPECT_EQ(FindStamp(trajectory, 10.0), 0u);
  EXPECT_EQ(FindStamp(trajectory, 10.14, 0.05), 1u);
  EXPECT_EQ(FindStamp(trajectory, 10.16, 0.05), 2u);
}

TEST(StampMatchingTest, RejectsStampsOutsideTolerance) {
  const geometry::Trajectory trajectory = ThreePoses();
  EXPECT_FALSE(FindStamp(trajectory, 10.05));
  EXPECT_FALSE(FindStamp(trajectory, 10.1015));
  EXPECT_FALSE(FindStamp(trajectory, 9.99));
  EXPECT_FALSE(FindStamp(trajectory, 10.21));
}

TEST(StampMatchingTest, RejectsEmptyTrajectoryNamingIt) {
  try {
    ValidateTrajectory({}, "truth trajectory");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "truth trajectory is empty");
  }
}

TEST(StampMatchingTest, RejectsUnsortedAndRepeatedStamps) {
  EXPECT_THROW(ValidateTrajectory({{1.0, {}}, {0.5, {}}}, "estimate"), std::invalid_argument);
  EXPECT_THROW(ValidateTrajectory({{1.0, {}}, {1.0, {}}}, "estimate"), std::invalid_argument);
  try {
    ValidateTrajectory({{1.0, {}}, {2.0, {}}, {1.5, {}}}, "estimate");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("strictly increasing, pose 2"), std::string::npos)
        << error.what();
  }
}

TEST(StampMatchingTest, RejectsNonFinitePoses) {
  geometry::Trajectory trajectory = ThreePoses();
  trajectory[1].pose.x_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ValidateTrajectory(trajectory, "estimate"), std::invalid_argument);
  EXPECT_NO_THROW(ValidateTrajectory(ThreePoses(), "estimate"));
}

}  // namespace
}  // namespace pena::eval
