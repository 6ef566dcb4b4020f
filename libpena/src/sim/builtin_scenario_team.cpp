// The built-in scenario "team": three firefighters and a robot search one building. Format and
// figures (route lengths, durations, plan differences): docs/scenarios.md.

#include <string_view>

#include "builtin_scenario_texts.hpp"

namespace pena::sim::detail {
namespace {

constexpr std::string_view kTeam = R"scn(pena-scenario 1
# A team mission: three firefighters and a robot enter a 50 x 35 m building through its one
# entrance a few seconds apart and search different parts of it with overlaps (the central
# and north corridors are walked by several). The a priori plan has the shell, the corridors
# and the facade rooms but not the inner partitions, the columns or the north partitions,
# and two walls are shifted (lobby west wall 0.3 m, east block west wall 0.4 m).
name team
ceiling 3.0
# Exterior 50 x 35 m; the only entrance is the 3 m double door at (25, 0).
wall 0 0 23.5 0
wall 26.5 0 50 0
wall 0 35 50 35
wall 0 0 0 35
wall 50 0 50 35
# Entrance lobby (x 20-30, y 0-8), open to the south corridor.
wall 20 0 20 4.5
wall 20 5.5 20 8
wall 30 0 30 4.5
wall 30 5.5 30 8
# Ring corridor, outer side: south y 8, west x 6, east x 44, north y 27.
wall 6 8 9 8
wall 10 8 16 8
wall 17 8 20 8
wall 30 8 33 8
wall 34 8 40 8
wall 41 8 44 8
wall 6 8 6 11
wall 6 12 6 17.5
wall 6 18.5 6 23.5
wall 6 24.5 6 27
wall 44 8 44 11.5
wall 44 12.5 44 17.5
wall 44 18.5 44 23.5
wall 44 24.5 44 27
wall 6 27 9.5 27
wall 10.5 27 17.5 27
wall 18.5 27 24.4 27
wall 25.6 27 31.5 27
wall 32.5 27 39.5 27
wall 40.5 27 44 27
# Rooms along the facade.
wall 6 0 6 3.5
wall 6 4.5 6 8
wall 44 0 44 3.5
wall 44 4.5 44 8
wall 13 0 13 8
wall 37 0 37 8
wall 0 8 6 8
wall 44 8 50 8
wall 0 15 6 15
wall 44 15 50 15
wall 0 21 6 21
wall 44 21 50 21
wall 0 27 6 27
wall 44 27 50 27
wall 6 27 6 30.5
wall 6 31.5 6 35
wall 44 27 44 30.5
wall 44 31.5 44 35
wall 14 27 14 35
wall 22 27 22 35
wall 28 27 28 35
wall 36 27 36 35
# Inner west block (x 8-24, y 10-25): six offices.
wall 8 10 10 10
wall 11 10 15.25 10
wall 16.25 10 20.75 10
wall 21.75 10 24 10
wall 8 25 11.5 25
wall 12.5 25 19.5 25
wall 20.5 25 24 25
wall 8 10 8 13.5
wall 8 14.5 8 25
wall 24 10 24 13.5
wall 24 14.5 24 21
wall 24 22 24 25
wall 8 17.5 24 17.5
wall 13 10 13 17.5
wall 18.5 10 18.5 17.5
wall 16 17.5 16 25
# Inner east block (x 26-42, y 10-25): three stores and a workshop hall with four columns.
wall 26 10 28 10
wall 29 10 33.25 10
wall 34.25 10 38.75 10
wall 39.75 10 42 10
wall 26 25 33.1 25
wall 34.9 25 42 25
wall 26 10 26 19.1
wall 26 20.9 26 25
wall 42 10 42 19.1
wall 42 20.9 42 25
wall 26 14 42 14
wall 31 10 31 14
wall 36.5 10 36.5 14
rect 30.75 17.25 31.25 17.75
rect 30.75 22.25 31.25 22.75
rect 36.75 17.25 37.25 17.75
rect 36.75 22.25 37.25 22.75
# The a priori plan.
apriori wall 0 0 23.5 0
apriori wall 26.5 0 50 0
apriori wall 0 35 50 35
apriori wall 0 0 0 35
apriori wall 50 0 50 35
apriori wall 19.7 0 19.7 4.5
apriori wall 19.7 5.5 19.7 8
apriori wall 30 0 30 4.5
apriori wall 30 5.5 30 8
apriori wall 6 8 9 8
apriori wall 10 8 16 8
apriori wall 17 8 20 8
apriori wall 30 8 33 8
apriori wall 34 8 40 8
apriori wall 41 8 44 8
apriori wall 6 8 6 11
apriori wall 6 12 6 17.5
apriori wall 6 18.5 6 23.5
apriori wall 6 24.5 6 27
apriori wall 44 8 44 11.5
apriori wall 44 12.5 44 17.5
apriori wall 44 18.5 44 23.5
apriori wall 44 24.5 44 27
apriori wall 6 27 9.5 27
apriori wall 10.5 27 17.5 27
apriori wall 18.5 27 24.4 27
apriori wall 25.6 27 31.5 27
apriori wall 32.5 27 39.5 27
apriori wall 40.5 27 44 27
apriori wall 6 0 6 3.5
apriori wall 6 4.5 6 8
apriori wall 44 0 44 3.5
apriori wall 44 4.5 44 8
apriori wall 13 0 13 8
apriori wall 37 0 37 8
apriori wall 0 8 6 8
apriori wall 44 8 50 8
apriori wall 0 15 6 15
apriori wall 44 15 50 15
apriori wall 0 21 6 21
apriori wall 44 21 50 21
apriori wall 0 27 6 27
apriori wall 44 27 50 27
apriori wall 6 27 6 30.5
apriori wall 6 31.5 6 35
apriori wall 44 27 44 30.5
apriori wall 44 31.5 44 35
apriori wall 8 10 10 10
apriori wall 11 10 15.25 10
apriori wall 16.25 10 20.75 10
apriori wall 21.75 10 24 10
apriori wall 8 25 11.5 25
apriori wall 12.5 25 19.5 25
apriori wall 20.5 25 24 25
apriori wall 8 10 8 13.5
apriori wall 8 14.5 8 25
apriori wall 24 10 24 13.5
apriori wall 24 14.5 24 21
apriori wall 24 22 24 25
apriori wall 26 10 28 10
apriori wall 29 10 33.25 10
apriori wall 34.25 10 38.75 10
apriori wall 39.75 10 42 10
apriori wall 26 25 33.1 25
apriori wall 34.9 25 42 25
apriori wall 26.4 10 26.4 19.1
apriori wall 26.4 20.9 26.4 25
apriori wall 42 10 42 19.1
apriori wall 42 20.9 42 25
# Smoke in the north room x 28-36.
smoke 28 27 36 35 3
# Steel entrance doors; machines in the workshop hall.
magnetic 25 1 2 20
magnetic 34 20 3 35
# ff1: the west wing and a north room.
entity ff1 human 23 3 90 start=0 speed=1.0
waypoint ff1 23 9
waypoint ff1 9.5 9
waypoint ff1 9.5 5.5 pause=3
waypoint ff1 9.5 9
waypoint ff1 7 9
waypoint ff1 7 11.5
waypoint ff1 3.5 11.5 pause=2
waypoint ff1 7 11.5
waypoint ff1 7 18
waypoint ff1 3.5 18 pause=3
waypoint ff1 7 18
waypoint ff1 7 24
waypoint ff1 3.5 24 pause=2
waypoint ff1 7 24
waypoint ff1 7 26
waypoint ff1 10 26
waypoint ff1 10 30.5 pause=2
waypoint ff1 10 26
waypoint ff1 18 26
waypoint ff1 18 30.5 pause=3
waypoint ff1 18 26
waypoint ff1 25 26
waypoint ff1 25 9
waypoint ff1 23 3
# ff2: the east wing and the smoky north room.
entity ff2 human 25 3 90 start=4 speed=1.0
waypoint ff2 25 9
waypoint ff2 40.5 9
waypoint ff2 40.5 5.5 pause=2
waypoint ff2 40.5 9
waypoint ff2 43 9
waypoint ff2 43 12
waypoint ff2 47 12 pause=3
waypoint ff2 43 12
waypoint ff2 43 18
waypoint ff2 47 18 pause=2
waypoint ff2 43 18
waypoint ff2 43 24
waypoint ff2 47 24 pause=2
waypoint ff2 43 24
waypoint ff2 43 26
waypoint ff2 40 26
waypoint ff2 40 30.5 pause=2
waypoint ff2 40 26
waypoint ff2 32 26
waypoint ff2 32 31 pause=5
waypoint ff2 32 26
waypoint ff2 25 26
waypoint ff2 25 9
waypoint ff2 25 3
# ff3: offices of the west block and the workshop hall.
entity ff3 human 27 3 90 start=8 speed=1.0
waypoint ff3 25 9
waypoint ff3 25 21.5
waypoint ff3 20 21.5 pause=3
waypoint ff3 25 21.5
waypoint ff3 25 20
waypoint ff3 30 20
waypoint ff3 34 17.5 pause=3
waypoint ff3 39.5 20
waypoint ff3 34 23
waypoint ff3 34 26
waypoint ff3 12 26
waypoint ff3 12 21.5 pause=3
waypoint ff3 12 26
waypoint ff3 25 26
waypoint ff3 25 9
waypoint ff3 15.75 9
waypoint ff3 15.75 13.5 pause=3
waypoint ff3 15.75 9
waypoint ff3 27 9
waypoint ff3 27 3
# robot1: through the hall, round the north and east corridors and back.
entity robot1 robot 28.5 4.5 90 start=12 speed=0.5
waypoint robot1 28.5 9
waypoint robot1 25 9
waypoint robot1 25 20
waypoint robot1 34 20
waypoint robot1 34 26
waypoint robot1 43 26
waypoint robot1 43 9
waypoint robot1 28.5 9
waypoint robot1 28.5 4.5
)scn";

}  // namespace

std::string_view TeamScenarioText() { return kTeam; }

}  // namespace pena::sim::detail
