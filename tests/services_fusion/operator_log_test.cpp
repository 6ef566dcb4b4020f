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

}  // namespace
}  // namespace pena::services
