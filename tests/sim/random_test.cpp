#include "pena/sim/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pena::sim {
namespace {

std::vector<double> Draw(Random random, int count) {
  std::vector<double> values;
  for (int i = 0; i < count; ++i) values.push_back(random.Normal());
  return values;
}

TEST(Random, SameSeedGivesTheSameSequence) {
  EXPECT_EQ(Draw(Random(42), 100), Draw(Random(42), 100));
  EXPECT_NE(Draw(Random(42), 100), Draw(Random(43), 100));
}

TEST(Random, DerivedStreamsAreIndependentOfDrawsFromTheParent) {
  Random parent(7);
  const Random fresh(7);
  parent.Uniform();
  parent.Normal();
  EXPECT_EQ(Draw(parent.Derive(3), 50), Draw(fresh.Derive(3), 50));
  EXPECT_NE(Draw(fresh.Derive(3), 50), Draw(fresh.Derive(4), 50));
}

TEST(Random, NormalHasZeroMeanAndUnitDeviation) {
  Random random(1);
  const int n = 200000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = random.Normal(2.0, 0.5);
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 2.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum_sq / n - mean * mean), 0.5, 0.01);
}

TEST(Random, UniformStaysInItsInterval) {
  Random random(5);
  double low = 1.0, high = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double u = random.Uniform(-1.0, 3.0);
    ASSERT_GE(u, -1.0);
    ASSERT_LT(u, 3.0);
    low = std::min(low, u);
    high = std::max(high, u);
  }
  EXPECT_LT(low, -0.99);
  EXPECT_GT(high, 2.99);
}

}  // namespace
}  // namespace pena::sim
