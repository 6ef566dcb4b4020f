// The built-in scenario "loop170": the Fig. 3 walk of Saarinen et al. (2004), one firefighter
// on a closed 170 m loop. Format and figures (route length, duration): docs/scenarios.md.

#include <string_view>

#include "builtin_scenario_texts.hpp"

namespace pena::sim::detail {
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

}  // namespace

std::string_view Loop170ScenarioText() { return kLoop170; }

}  // namespace pena::sim::detail
