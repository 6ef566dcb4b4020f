#pragma once
// The corridor mission the entity process tests drive: two rooms off a 24 m corridor, one robot
// driving about 20 m along it (about 40 s of mission time, 160 scans at 4 Hz).

namespace pena::testing {

inline constexpr const char* kCorridorScenario = R"scn(pena-scenario 1
name services_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity robot1 robot 2 2 0 speed=0.8
waypoint robot1 22 2
waypoint robot1 22 1.5
waypoint robot1 13.5 1.5
)scn";

}  // namespace pena::testing
