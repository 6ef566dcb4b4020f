#include "pena/sim/truth_relations.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pena::sim {
namespace {

// A straight walk at 1 m/s along +x with a scan every 0.25 s.
geometry::Trajectory StraightWalk(double duration_s) {
  geometry::Trajectory truth;
  for (int i = 0; i * 0.25 <= duration_s; ++i) truth.push_back({i / 4.0, {i / 4.0, 0.0, 0.0}});
  return truth;
}

TEST(TruthRelations, ConsecutivePairsPlusTwoAndFourSecondsFromOneAnchorPerSecond) {
  const geometry::Trajectory truth = StraightWalk(10.0);  // 41 poses
  const auto relations = TruthRelations(truth);
  std::size_t consecutive = 0, two = 0, four = 0;
  for (const auto& relation : relations) {
    const double dt = relation.t2_s - relation.t1_s;
    EXPECT_NEAR(relation.motion.x_m, dt, 1e-12);  // 1 m/s straight ahead
    EXPECT_NEAR(relation.motion.y_m, 0.0, 1e-12);
    consecutive += std::abs(dt - 0.25) < 1e-9;
    two += std::abs(dt - 2.0) < 1e-9;
    four += std::abs(dt - 4.0) < 1e-9;
  }
  EXPECT_EQ(consecutive, 40u);
  EXPECT_EQ(two, 9u);   // anchors at 0..8 s
  EXPECT_EQ(four, 7u);  // anchors at 0..6 s
  EXPECT_EQ(relations.size(), 56u);
}

TEST(TruthRelations, MotionIsExpressedInTheFirstPose) {
  geometry::Trajectory truth = {{0.0, {1.0, 1.0, M_PI / 2}}, {0.25, {1.0, 2.0, M_PI / 2}}};
  const auto relations = TruthRelations(truth);
  ASSERT_EQ(relations.size(), 1u);
  EXPECT_NEAR(relations[0].motion.x_m, 1.0, 1e-12);  // forward in the body frame
  EXPECT_NEAR(relations[0].motion.y_m, 0.0, 1e-12);
}

}  // namespace
}  // namespace pena::sim
