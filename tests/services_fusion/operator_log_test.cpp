#include "operator_log.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace pena::services {
namespace {

TEST(OperatorLog, RemembersAppliedCorrectionsAcrossAReopen) {
  const auto path = std::filesystem::path(testing::TempDir()) / "operator_log_test.csv";
  std::filesystem::remove(path);
  {
    OperatorLog log(path);
    EXPECT_FALSE(log.Contains("op/1-1"));
    log.Append({"op/1-1", "ff1", "op", "rotate", 12.5, {0.1, -0.2, 0.35}});
    EXPECT_TRUE(log.Contains("op/1-1"));
  }
  // A crash while writing leaves a torn last line: it does not count.
  { std::ofstream(path, std::ios::app) << "op/1-2,ff1,op,rot"; }
  const OperatorLog reopened(path);
  EXPECT_TRUE(reopened.Contains("op/1-1"));
  EXPECT_FALSE(reopened.Contains("op/1-2"));
  EXPECT_EQ(reopened.size(), 1u);
}

// Undo goes from the end: the last move of an entity in force, across a reopen (kill -9).
TEST(OperatorLog, KnowsTheLastMoveInForceAcrossUndosAndAReopen) {
  const auto path = std::filesystem::path(testing::TempDir()) / "operator_log_undo_test.csv";
  std::filesystem::remove(path);
  {
    OperatorLog log(path);
    log.Append({"op/1", "ff1", "op", "rotate", 12.5, {0.1, -0.2, 0.35}});
    log.Append({"op/2", "ff1", "op", "translate", 20.0, {1.0, 0.0, 0.0}});
    log.Append({"op/3", "ff2", "op", "translate", 21.0, {0.0, 1.0, 0.0}});
    EXPECT_EQ(log.LastInForce("ff1"), "op/2");
    log.Append({"op/4", "ff1", "op", "undo", 20.0, {-1.0, 0.0, 0.0}, "op/2"});
    EXPECT_EQ(log.LastInForce("ff1"), "op/1");
  }
  const OperatorLog reopened(path);
  EXPECT_EQ(reopened.LastInForce("ff1"), "op/1");
  EXPECT_EQ(reopened.LastInForce("ff2"), "op/3");
  EXPECT_EQ(reopened.LastInForce("ff3"), "");
  const OperatorLogRecord* undo = reopened.Find("op/4");
  ASSERT_NE(undo, nullptr);
  EXPECT_EQ(undo->kind, "undo");
  EXPECT_EQ(undo->undoes, "op/2");
  EXPECT_DOUBLE_EQ(undo->corrected_from_wrong.x_m, -1.0);
  const OperatorLogRecord* rotate = reopened.Find("op/1");
  ASSERT_NE(rotate, nullptr);
  EXPECT_DOUBLE_EQ(rotate->from_stamp_s, 12.5);
  EXPECT_NEAR(rotate->corrected_from_wrong.theta_rad, 0.35, 1e-12);
}

}  // namespace
}  // namespace pena::services
