#include "pena/eval/mean_std.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pena::eval {
namespace {

TEST(MeanStdTest, UsesPopulationStandardDeviation) {
  const MeanStd result = ComputeMeanStd({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(result.mean, 2.5);
  // Deviations -1.5, -0.5, 0.5, 1.5: squares sum to 5, divided by N = 4.
  EXPECT_DOUBLE_EQ(result.std, std::sqrt(1.25));
}

TEST(MeanStdTest, SingleValueHasZeroSpread) {
  const MeanStd result = ComputeMeanStd({7.0});
  EXPECT_DOUBLE_EQ(result.mean, 7.0);
  EXPECT_DOUBLE_EQ(result.std, 0.0);
}

TEST(MeanStdTest, EmptySampleGivesZeros) {
  const MeanStd result = ComputeMeanStd({});
  EXPECT_EQ(result.mean, 0.0);
  EXPECT_EQ(result.std, 0.0);
}

}  // namespace
}  // namespace pena::eval
