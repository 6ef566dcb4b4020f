#pragma once
// Small buildings and helpers shared by the simulator tests.

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::sim::testing {

constexpr double kDeg = std::numbers::pi / 180.0;

// The four walls of an axis-aligned rectangle.
inline std::vector<geometry::Segment2> Rectangle(double x0, double y0, double x1, double y1) {
  const Eigen::Vector2d a(x0, y0), b(x1, y0), c(x1, y1), d(x0, y1);
  return {{a, b}, {b, c}, {c, d}, {d, a}};
}

// A 2 m wide corridor loop around a 16 x 8 m block (outer walls 20 x 12 m); one entity walks
// (or drives) the corridor's centre line `laps` times, starting at (1, 1) facing +x.
inline Scenario CorridorLoop(sensors::EntityKind kind = sensors::EntityKind::kHuman, int laps = 1) {
  Scenario scenario;
  scenario.name = "corridor-loop";
  scenario.ceiling_height_m = 2.6;
  scenario.walls = Rectangle(0.0, 0.0, 20.0, 12.0);
  for (const auto& wall : Rectangle(2.0, 2.0, 18.0, 10.0)) scenario.walls.push_back(wall);
  EntitySpec entity;
  entity.id = kind == sensors::EntityKind::kHuman ? "ff1" : "robot1";
  entity.kind = kind;
  entity.start = {1.0, 1.0, 0.0};
  entity.cruise_speed_m_s = kind == sensors::EntityKind::kHuman ? 1.0 : 0.5;
  entity.route = {{{19.0, 1.0}, 0.0}, {{19.0, 11.0}, 0.0}, {{1.0, 11.0}, 2.0}, {{1.0, 1.0}, 0.0}};
  entity.laps = laps;
  scenario.entities.push_back(entity);
  return scenario;
}

// Options with exact sensors: no range noise, no drop-outs.
inline SimulationOptions NoiseFreeLaser(std::uint64_t seed = 1) {
  SimulationOptions options;
  options.seed = seed;
  options.laser_noise.range_noise_sd_m = 0.0;
  options.laser_noise.dropout_probability = 0.0;
  return options;
}

}  // namespace pena::sim::testing
