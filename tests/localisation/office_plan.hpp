#pragma once
// The built-in `office` scenario's true walls and its a priori plan (partial, four walls shifted),
// and perfect scans of the true walls: the situation of the paper's Fig. 9 without sensor noise.

#include <numbers>
#include <stdexcept>
#include <vector>

#include "pena/localisation/map_localiser.hpp"
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

// One update of `localiser` at `pose` (a new keyframe, so a round runs) with a perfect odometry
// and a perfect scan of the true walls `truth`, stamped `stamp_s`.
inline std::optional<MapCorrection> PerfectRound(MapLocaliser& localiser, const VirtualScanner& truth,
                                                 const geometry::Pose2& pose, double stamp_s) {
  odometry::OdometryEstimate estimate;
  estimate.stamp_s = stamp_s;
  estimate.world_from_body = pose;
  estimate.reference_changed = true;
  return localiser.Update(truth.Scan(pose, OfficeLaser(), 361, stamp_s), estimate);
}

}  // namespace pena::localisation::testing
