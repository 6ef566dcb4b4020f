// The builtin team scenario's entities (robot1: level laser, wheel odometry; ff1-ff3: people),
// simulated once per test binary with the default options (seed 1), shared by the odometry tests.
#pragma once

#include <stdexcept>
#include <string>

#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::odometry::testing {

inline const sim::EntityRecording& TeamEntity(const std::string& id) {
  static const sim::SimulationResult team = [] {
    const sim::Scenario scenario =
        sim::ParseScenario(std::string(*sim::BuiltinScenarioText("team")), "builtin:team");
    return sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  }();
  for (const auto& entity : team.entities) {
    if (entity.id == id) return entity;
  }
  throw std::runtime_error("no entity " + id + " in the team scenario");
}

}  // namespace pena::odometry::testing
