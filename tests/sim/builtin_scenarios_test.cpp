// The built-in scenarios run through the simulator: walkers keep off the walls, humans see the
// floor or ceiling in at least 5 % of scans (the paper's central problem), robots never do.
#include <gtest/gtest.h>

#include <string>

#include "pena/sim/human_motion.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::sim {
namespace {

Scenario Builtin(const std::string& name) {
  const auto text = BuiltinScenarioText(name);
  if (!text) throw std::runtime_error("no built-in scenario " + name);
  return ParseScenario(*text, "builtin:" + name);
}

class BuiltinScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScenario, HumansHitFloorOrCeilingInAtLeastFivePercentOfScans) {
  const Scenario scenario = Builtin(GetParam());
  ASSERT_EQ(ValidateScenario(scenario), "");
  const SimulationResult result = Simulator().Run(scenario);
  ASSERT_EQ(result.entities.size(), scenario.entities.size());
  for (const EntityRecording& entity : result.entities) {
    ASSERT_GT(entity.scans, 100u) << entity.id;
    const double fraction =
        static_cast<double>(entity.scans_with_floor_or_ceiling) / static_cast<double>(entity.scans);
    if (entity.kind == sensors::EntityKind::kHuman) {
      EXPECT_GE(fraction, 0.05) << entity.id;
    } else {
      EXPECT_EQ(fraction, 0.0) << entity.id;
    }
  }
  EXPECT_FALSE(result.observed.empty());
}

TEST_P(BuiltinScenario, WalkersKeepOffTheWalls) {
  const Scenario scenario = Builtin(GetParam());
  for (const EntitySpec& entity : scenario.entities) {
    if (entity.kind != sensors::EntityKind::kHuman) continue;
    Random random(1);
    const TrueMotion motion = HumanMotion().Generate(entity, scenario.walls, random);
    double closest = 1e9;
    for (const TrueState& state : motion.states) {
      for (const auto& wall : scenario.walls) {
        closest = std::min(closest, geometry::DistanceToSegment(wall, {state.world_from_body.x_m,
                                                                       state.world_from_body.y_m}));
      }
    }
    EXPECT_GT(closest, 0.2) << entity.id;
  }
}

INSTANTIATE_TEST_SUITE_P(Sim, BuiltinScenario, ::testing::Values("loop170", "office", "team"));

}  // namespace
}  // namespace pena::sim
