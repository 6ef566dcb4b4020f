#pragma once
// The built-in `office` scenario's true walls and its a priori plan (partial, four walls shifted),
// and perfect scans of the true walls: the situation of the paper's Fig. 9 without sensor noise.

#include <numbers>
#include <stdexcept>
#include <vector>

#include "pena/localisation/virtual_scanner.hpp"
#include "pena/sim/scenario.hpp"

namespace pena::localisation::testing {

inline sim::Scenario OfficeScenario() {
  const auto text = sim::BuiltinScenarioText("office");
  if (!text) throw std::runtime_error("no built-in office scenario");
  return sim::ParseScenario(*text, "office");
}

// The simulator's laser: 361 beams over 180 deg, 30 m.
inline sensors::LaserGeometry OfficeLaser() {
  return {-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
}

}  // namespace pena::localisation::testing
