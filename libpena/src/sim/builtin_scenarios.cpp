// The built-in scenarios as scenario texts (format: docs/scenarios.md). Figures per scenario
// (route lengths, durations, a priori differences) are in docs/scenarios.md.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

constexpr std::string_view kLoop170 = R"scn(pena-scenario 1
# The Fig. 3 walk of Saarinen et al. (2004): one firefighter on a closed 170 m loop of 2 m
# corridors around four blocks of rooms, about 231 s. Features: door gaps, a lift recess, an alcove,
# a four-way crossing at (33, 21), a pillar hall, and a plain 22 m stretch (top corridor, x 37-59).
name loop170
ceiling 2.6
# Exterior, 66 x 43 m; the entrance vestibule at the bottom left has the only outside door.
wall 0 0 7.1 0
wall 8.9 0 66 0
wall 0 43 66 43
wall 0 0 0 43
wall 66 0 66 43
# Ring corridor, outer side (rooms along the facade open onto it).
wall 0 5 7 5
wall 9 5 11.7 5
wall 12.7 5 17.7 5
wall 18.7 5 23.7 5
wall 24.7 5 29.7 5
wall 30.7 5 35.7 5
wall 36.7 5 41.7 5
wall 42.7 5 47.7 5
wall 48.7 5 54.9 5
wall 56.1 5 66 5
wall 5 5 5 5.8
wall 5 6.8 5 11.8
wall 5 12.8 5 17.8
wall 5 18.8 5 23.8
wall 5 24.8 5 30.9
wall 5 32.1 5 38
wall 5 38 5.8 38
wall 6.8 38 11.8 38
wall 12.8 38 17.8 38
wall 18.8 38 23.8 38
wall 24.8 38 30.5 38
wall 31.5 38 36.4 38
wall 37.6 38 61 38
wall 61 5 61 5.8
wall 61 6.8 61 17
wall 61 18 61 19.8
wall 61 20.8 61 26.8
wall 61 27.8 61 33
wall 61 34 61 38
# Facade rooms: partitions between the ring and the exterior.
wall 5 0 5 5
wall 11 0 11 5
wall 17 0 17 5
wall 23 0 23 5
wall 29 0 29 5
wall 35 0 35 5
wall 41 0 41 5
wall 47 0 47 5
wall 53 0 53 5
wall 61 0 61 5
wall 0 5 5 5
wall 0 11 5 11
wall 0 17 5 17
wall 0 23 5 23
wall 0 29 5 29
wall 5 38 5 43
wall 11 38 11 43
wall 17 38 17 43
wall 23 38 23 43
wall 29 38 29 43
wall 36 38 36 43
wall 61 38 61 43
wall 61 5 66 5
wall 61 12 66 12
wall 61 19 66 19
wall 61 26 66 26
wall 61 31 66 31
# Alcove (hose cabinet) in the right corridor, 2 m long and 0.8 m deep.
polyline 61 14 61.8 14 61.8 16 61 16
# Inner block south-west (x 7-32, y 7-20), its north side steps back for the pillar hall.
wall 7 7 8 7
wall 9 7 14 7
wall 15 7 20 7
wall 21 7 27 7
wall 28 7 32 7
wall 7 7 7 16
wall 7 17 7 20
wall 32 7 32 9.5
wall 32 10.5 32 16
wall 32 17 32 20
wall 7 20 12 20
wall 12 18 16 18
wall 17 18 22 18
wall 23 18 24 18
wall 24 20 32 20
wall 7 13 32 13
wall 13 7 13 13
wall 19 7 19 13
wall 26 7 26 13
wall 12 13 12 20
wall 24 13 24 20
wall 18 13 18 18
# Inner block north-west (x 7-32, y 22-36).
wall 7 22 12 22
wall 12 24 16 24
wall 17 24 22 24
wall 23 24 24 24
wall 24 22 32 22
wall 7 36 8 36
wall 9 36 15 36
wall 16 36 22 36
wall 23 36 28 36
wall 29 36 32 36
wall 7 22 7 25
wall 7 26 7 36
wall 32 22 32 25.5
wall 32 26.5 32 30.5
wall 32 31.5 32 36
wall 7 29 32 29
wall 14 29 14 36
wall 21 29 21 36
wall 27 29 27 36
wall 12 22 12 29
wall 24 22 24 29
wall 18 24 18 29
# Pillar hall on the middle corridor: six 0.4 m columns beside the walking line y = 21.
rect 14.8 19.3 15.2 19.7
rect 14.8 22.3 15.2 22.7
rect 17.8 19.3 18.2 19.7
rect 17.8 22.3 18.2 22.7
rect 20.8 19.3 21.2 19.7
rect 20.8 22.3 21.2 22.7
# Inner block south-east (x 34-59, y 7-20) with the lift: recess in the corridor wall, shaft behind.
wall 34 7 35.5 7
wall 36.5 7 40 7
wall 43 7 46 7
wall 47 7 51.5 7
wall 52.5 7 59 7
polyline 40 7 40 8.5 43 8.5 43 7
rect 40 8.5 43 11
wall 34 7 34 16.5
wall 34 17.5 34 20
wall 59 7 59 9.5
wall 59 10.5 59 20
wall 34 20 37.5 20
wall 38.5 20 44.5 20
wall 45.5 20 52.5 20
wall 53.5 20 59 20
wall 34 14 59 14
wall 40 7 40 14
wall 50 7 50 14
wall 43 11 43 14
wall 42 14 42 20
wall 50 14 50 20
# Inner block north-east (x 34-59, y 22-36): its top wall is the plain 22 m stretch of the top corridor.
wall 34 22 36 22
wall 37 22 43.5 22
wall 44.5 22 51.5 22
wall 52.5 22 59 22
wall 34 36 59 36
wall 34 22 34 24.5
wall 34 25.5 34 31.5
wall 34 32.5 34 36
wall 59 22 59 25.5
wall 59 26.5 59 32.5
wall 59 33.5 59 36
wall 34 29 59 29
wall 41 22 41 29
wall 48 22 48 29
wall 45 29 45 36
# Compass disturbances: the lift, the steel columns of the hall, the switch room behind the right corridor.
magnetic 41.5 8.5 3 30
magnetic 18 21 2.5 20
magnetic 61.5 24 2 40
# ff1 walks east, north, west, down the centre corridor through the crossing, west, south.
entity ff1 human 9 6 0 speed=0.8
waypoint ff1 60 6
waypoint ff1 60 37
waypoint ff1 33 37
waypoint ff1 33 21 pause=4
waypoint ff1 6 21
waypoint ff1 6 6
waypoint ff1 9 6
)scn";

constexpr std::string_view kOffice = R"scn(pena-scenario 1
# The Fig. 9 situation of Saarinen et al. (2004): an office floor whose a priori plan lacks two
# rooms at the bottom (the annex) and two small rooms on the left (the west wing), and has four
# walls shifted by 0.3-0.6 m. The firefighter leaves the mapped area, searches those rooms and
# comes back to the entrance.
name office
ceiling 2.7
# Main block 38 x 14 m (x 4-42, y 8-22): one corridor (y 13-15), the entrance at its east end.
wall 4 22 42 22
wall 4 8 21 8
wall 23 8 42 8
wall 42 8 42 13.1
wall 42 14.9 42 22
wall 4 8 4 13
wall 4 15 4 22
# Corridor walls and rooms north of it (doors 1.0 m; the entrance hall has a 1.6 m opening).
wall 4 15 6.5 15
wall 7.5 15 12.5 15
wall 13.5 15 19 15
wall 20 15 24.5 15
wall 25.5 15 28 15
wall 28 15 30 15
wall 31 15 34 15
wall 34 15 36.2 15
wall 37.8 15 42 15
wall 10 15 10 22
wall 22 15 22 22
wall 28 15 28 22
wall 34 15 34 22
wall 16 15 16 22
# Rooms south of the corridor; the 2 m passage at x 21-23 leads down to the annex.
wall 4 13 6 13
wall 7 13 11.5 13
wall 12.5 13 17.5 13
wall 18.5 13 21 13
wall 23 13 25.5 13
wall 26.5 13 31.5 13
wall 32.5 13 37.9 13
wall 39.1 13 42 13
wall 9 8 9 13
wall 15 8 15 13
wall 35 8 35 13
wall 29 8 29 13
wall 21 8 21 13
wall 23 8 23 13
# Annex (x 14-30, y 0-8, missing from the plan): two rooms either side of the passage.
wall 21 0 21 5
wall 21 6 21 8
wall 23 0 23 3
wall 23 4 23 8
wall 14 0 30 0
wall 14 0 14 8
wall 30 0 30 8
# West wing (x 0-4, y 9-19, missing from the plan): a vestibule and two small rooms.
wall 0 9 0 19
wall 0 9 4 9
wall 0 19 4 19
wall 0 13 1.5 13
wall 2.5 13 4 13
wall 0 15 1.5 15
wall 2.5 15 4 15
# The a priori plan (partial and partly wrong).
apriori wall 4 22 42 22
# The plan shows the south facade unbroken: the passage to the annex is not on it.
apriori wall 4 8 42 8
apriori wall 42.3 8 42.3 13.1
apriori wall 42.3 14.9 42.3 22
# The plan ends the building at x = 4: the west wing with its two small rooms is not on it.
apriori wall 4 8 4 22
apriori wall 4 15 6.5 15
apriori wall 7.5 15 12.5 15
apriori wall 13.5 15 19 15
apriori wall 20 15 24.5 15
apriori wall 25.5 15 28 15
apriori wall 28 15.4 30 15.4
apriori wall 31 15.4 34 15.4
apriori wall 34 15 36.2 15
apriori wall 37.8 15 42 15
apriori wall 10 15 10 22
apriori wall 22 15 22 22
apriori wall 28 15 28 22
apriori wall 34 15 34 22
apriori wall 16.5 15 16.5 22
apriori wall 4 13 6 13
apriori wall 7 13 11.5 13
apriori wall 12.5 13 17.5 13
apriori wall 18.5 13 21 13
apriori wall 23 13 25.5 13
apriori wall 26.5 13 31.5 13
apriori wall 32.5 13 37.9 13
apriori wall 39.1 13 42 13
apriori wall 9 8 9 13
apriori wall 15 8 15 13
apriori wall 35 8 35 13
apriori wall 28.4 8 28.4 13
apriori wall 21 8 21 13
apriori wall 23 8 23 13
# Smoke fills the archive room north of the corridor (x 28-34).
smoke 28 15 34 22 2.5
# Steel door frame and stairs at the passage to the annex.
magnetic 22 8 2 25
entity ff1 human 40 14 180 speed=0.9
waypoint ff1 30.5 14
waypoint ff1 30.5 18.5 pause=5
waypoint ff1 30.5 14
waypoint ff1 22 14
waypoint ff1 22 5.5
waypoint ff1 19 5.5
waypoint ff1 17 4 pause=4
waypoint ff1 19 5.5
waypoint ff1 22 5.5
waypoint ff1 22 3.5
waypoint ff1 25 3.5
waypoint ff1 27 5 pause=4
waypoint ff1 25 3.5
waypoint ff1 22 3.5
waypoint ff1 22 14
waypoint ff1 2 14
waypoint ff1 2 11 pause=3
waypoint ff1 2 14
waypoint ff1 2 17 pause=3
waypoint ff1 2 14
waypoint ff1 40 14
)scn";

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

struct Builtin {
  std::string_view name;
  std::string_view text;
};

constexpr std::array<Builtin, 3> kBuiltins{{
    {"loop170", kLoop170},
    {"office", kOffice},
    {"team", kTeam},
}};

}  // namespace

std::vector<std::string> BuiltinScenarioNames() {
  std::vector<std::string> names;
  for (const Builtin& builtin : kBuiltins) names.emplace_back(builtin.name);
  return names;
}

std::optional<std::string_view> BuiltinScenarioText(std::string_view name) {
  for (const Builtin& builtin : kBuiltins) {
    if (builtin.name == name) return builtin.text;
  }
  return std::nullopt;
}

}  // namespace pena::sim
