// The built-in scenario "office": the Fig. 9 office floor whose a priori plan is partial and
// partly wrong. Format and figures (route length, plan differences): docs/scenarios.md.

#include <string_view>

#include "builtin_scenario_texts.hpp"

namespace pena::sim::detail {
namespace {

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

}  // namespace

std::string_view OfficeScenarioText() { return kOffice; }

}  // namespace pena::sim::detail
