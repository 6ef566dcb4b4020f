#pragma once
// The texts of the built-in scenarios, one file each (builtin_scenario_<name>.cpp); the registry
// that names them is builtin_scenarios.cpp. Internal to the sim module.

#include <string_view>

namespace pena::sim::detail {

std::string_view Loop170ScenarioText();  // "loop170": the paper's Fig. 3 loop
std::string_view OfficeScenarioText();   // "office": the paper's Fig. 9 office floor
std::string_view TeamScenarioText();     // "team": three firefighters and a robot

}  // namespace pena::sim::detail
