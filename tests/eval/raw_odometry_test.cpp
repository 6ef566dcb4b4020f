// Reproduces the raw-odometry figures of data/README.md on the Freiburg benchmark:
// the FLASER odometry pose fields, scored against the ground-truth relations.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <variant>

#include "pena/eval/relation_error.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/trajectory_io.hpp"
#include "test_data.hpp"

namespace pena::eval {
namespace {

const std::filesystem::path kFreiburgDir = pena::testing::DataPath("freiburg");

// The odometry pose of every scan, stamped with the scan's stamp (the relations' stamps).
geometry::Trajectory ScanOdometry(const std::filesystem::path& log_path) {
  geometry::Trajectory trajectory;
  const auto log = io::OpenCarmenLog(log_path);
  while (const auto record = log->Next()) {
    const auto* scan = std::get_if<sensors::LaserScan>(&*record);
    if (scan && scan->odometry_pose) trajectory.push_back({scan->stamp_s, *scan->odometry_pose});
  }
  return trajectory;
}

RelationErrorSummary ScoreRawOdometry(const std::string& name) {
  const auto log_path = kFreiburgDir / (name + ".clf.gz");
  const auto relations_path = kFreiburgDir / (name + ".relations");
  EXPECT_TRUE(std::filesystem::exists(log_path)) << log_path;
  return EvaluateRelations(ScanOdometry(log_path), io::ReadRelations(relations_path));
}

// The README rounds the figures to two significant digits ("about 7.4 m"); +-10 % covers that
// rounding and small differences in how the odometry is interpolated at scan time, and still fails
// on a wrong metric (e.g. errors squared, or relations composed the other way round) or a wrong
// stamp match (which skips relations or pairs the wrong poses).
TEST(RawOdometryTest, IntelScoresAboutSevenPointFourMetres) {
  const RelationErrorSummary summary = ScoreRawOdometry("intel");
  EXPECT_EQ(summary.relations_skipped, 0u);
  EXPECT_EQ(summary.relations_used, 2984u);  // lines in intel.relations
  EXPECT_NEAR(summary.translation_m.mean, 7.4, 0.74);
}

TEST(RawOdometryTest, AcesScoresAboutHalfAMetre) {
  const RelationErrorSummary summary = ScoreRawOdometry("aces");
  EXPECT_EQ(summary.relations_skipped, 0u);
  EXPECT_NEAR(summary.translation_m.mean, 0.55, 0.055);
}

TEST(RawOdometryTest, MitCsailScoresAboutOnePointSevenMetres) {
  const RelationErrorSummary summary = ScoreRawOdometry("mit-csail");
  EXPECT_EQ(summary.relations_skipped, 0u);
  EXPECT_NEAR(summary.translation_m.mean, 1.7, 0.17);
}

}  // namespace
}  // namespace pena::eval
