// The builtin team scenario's entities (robot1: level laser, wheel odometry; ff1-ff3: people),
// simulated once per test binary with the default options (seed 1), shared by the odometry tests.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
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

// The odometry's estimates for `records` (the entity's own or altered ones), started at the
// entity's true start pose.
inline std::vector<OdometryEstimate> ReplayRecords(const sim::EntityRecording& entity,
                                                   const std::vector<sensors::SensorRecord>& records,
                                                   const LaserOdometryOptions& options) {
  LaserOdometry odometry(options, entity.kind, entity.truth.front().world_from_body, entity.start_s);
  std::vector<OdometryEstimate> estimates;
  for (const auto& record : records) {
    if (auto estimate = odometry.Add(record)) estimates.push_back(*estimate);
  }
  return estimates;
}

}  // namespace pena::odometry::testing
