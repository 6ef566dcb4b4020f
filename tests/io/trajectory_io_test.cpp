// TUM trajectories and Freiburg relations: round trips and bad rows.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>

#include "io_test_util.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/trajectory_io.hpp"

namespace pena::io {
namespace {

using testing::WriteText;

geometry::Trajectory MakeTrajectory() {
  geometry::Trajectory trajectory;
  for (int i = 0; i < 50; ++i) {
    const double yaw = -3.1 + 0.127 * i;  // sweeps through +-pi
    trajectory.push_back({976052857.337530 + 0.25 * i, {0.1 * i, -0.05 * i * i, yaw}});
  }
  return trajectory;
}

std::size_t ErrorLine(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.line();
  }
  ADD_FAILURE() << "no InputError";
  return 0;
}

TEST(TrajectoryIo, TumRoundTripKeepsStampsPositionsAndYaw) {
  const geometry::Trajectory written = MakeTrajectory();
  const auto path = testing::TempPath("traj.tum");
  WriteTum(path, written);
  const geometry::Trajectory read = ReadTum(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_DOUBLE_EQ(read[i].stamp_s, written[i].stamp_s);  // 6 decimals hold microseconds
    EXPECT_DOUBLE_EQ(read[i].pose.x_m, written[i].pose.x_m);
    EXPECT_DOUBLE_EQ(read[i].pose.y_m, written[i].pose.y_m);
    EXPECT_NEAR(geometry::NormalizeAngle(read[i].pose.theta_rad - written[i].pose.theta_rad), 0.0,
                1e-12);
  }
}

TEST(TrajectoryIo, TumYawComesFromTheQuaternion) {
  // 90 deg about z, given as a non-unit quaternion, plus a comment line.
  const auto path = WriteText("yaw.tum", "# ts x y z qx qy qz qw\n1.0 2 3 0 0 0 2 2\n");
  const auto read = ReadTum(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_NEAR(read[0].pose.theta_rad, std::numbers::pi / 2, 1e-12);
}

TEST(TrajectoryIo, TumBadRowsNameTheirLine) {
  EXPECT_EQ(ErrorLine([&] { ReadTum(WriteText("short.tum", "1 0 0 0 0 0 0 1\n2 0 0 0 0 1\n")); }),
            2u);
  EXPECT_EQ(ErrorLine([&] { ReadTum(WriteText("text.tum", "# c\n1 0 0 0 0 0 0 1\n2 a 0 0 0 0 0 1\n")); }),
            3u);
  EXPECT_EQ(ErrorLine([&] { ReadTum(WriteText("back.tum", "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n")); }),
            2u);
  EXPECT_EQ(ErrorLine([&] { ReadTum(WriteText("zero.tum", "1 0 0 0 0 0 0 0\n")); }), 1u);
  EXPECT_EQ(ErrorLine([&] { ReadTum(testing::TempPath("missing.tum")); }), 0u);
}

TEST(TrajectoryIo, RelationsRoundTrip) {
  std::vector<geometry::Relation> written;
  for (int i = 0; i < 20; ++i) {
    written.push_back({976052905.167303 + i, 976052911.885496 + i, {0.3 - 0.01 * i, 0.02 * i, -1.6 + 0.1 * i}});
  }
  const auto path = testing::TempPath("out.relations");
  WriteRelations(path, written);
  const auto read = ReadRelations(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_DOUBLE_EQ(read[i].t1_s, written[i].t1_s);
    EXPECT_DOUBLE_EQ(read[i].t2_s, written[i].t2_s);
    EXPECT_DOUBLE_EQ(read[i].motion.x_m, written[i].motion.x_m);
    EXPECT_DOUBLE_EQ(read[i].motion.y_m, written[i].motion.y_m);
    EXPECT_DOUBLE_EQ(read[i].motion.theta_rad, written[i].motion.theta_rad);
  }
}

TEST(TrajectoryIo, ReadsFreiburgRelationsFile) {
  const auto path = pena::testing::DataPath("freiburg/mit-csail.relations");
  std::ifstream in(path);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  const auto relations = ReadRelations(path);
  ASSERT_GT(lines, 0u);
  EXPECT_EQ(relations.size(), lines);
  // First line: 1134864645.90321 1134864646.32420 0.31293 0.02935 0 0 0 0.24198
  EXPECT_DOUBLE_EQ(relations[0].t1_s, 1134864645.90321);
  EXPECT_DOUBLE_EQ(relations[0].motion.x_m, 0.31293);
  EXPECT_DOUBLE_EQ(relations[0].motion.theta_rad, 0.24198);
}

TEST(TrajectoryIo, RelationsBadRowsNameTheirLine) {
  EXPECT_EQ(ErrorLine([&] {
              ReadRelations(WriteText("bad.relations", "1 2 0 0 0 0 0 0.1\n1 2 0 0 0 0 nan 0.1\n"));
            }),
            2u);
  EXPECT_EQ(ErrorLine([&] { ReadRelations(WriteText("few.relations", "1 2 0 0 0 0 0\n")); }), 1u);
}

}  // namespace
}  // namespace pena::io
