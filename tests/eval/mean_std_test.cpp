#include "pena/eval/mean_std.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

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

TEST(SpreadTest, NearestRankQuantilesOfAnUnsortedSample) {
  std::vector<double> values;
  for (int k = 20; k >= 1; --k) values.push_back(static_cast<double>(k));  // 20, 19, ..., 1
  const Spread spread = ComputeSpread(values);
  EXPECT_DOUBLE_EQ(spread.median, 10.0);  // rank ceil(0.5 * 20) = 10
  EXPECT_DOUBLE_EQ(spread.p95, 19.0);     // rank ceil(0.95 * 20) = 19
  EXPECT_DOUBLE_EQ(spread.max, 20.0);
  EXPECT_DOUBLE_EQ(Quantile(values, 0.0), 1.0);
}

TEST(SpreadTest, OneLargeErrorShowsInTheMaxNotTheMedian) {
  std::vector<double> values(99, 0.05);
  values.push_back(93.0);
  const Spread spread = ComputeSpread(values);
  EXPECT_DOUBLE_EQ(spread.median, 0.05);
  EXPECT_DOUBLE_EQ(spread.p95, 0.05);
  EXPECT_DOUBLE_EQ(spread.max, 93.0);
}

TEST(SpreadTest, EmptySampleGivesZerosAndBadFractionsAreRefused) {
  const Spread spread = ComputeSpread({});
  EXPECT_EQ(spread.median, 0.0);
  EXPECT_EQ(spread.max, 0.0);
  EXPECT_THROW(Quantile({1.0}, 1.5), std::invalid_argument);
  EXPECT_THROW(Quantile({1.0}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace pena::eval
