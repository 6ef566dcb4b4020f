// The registry of the built-in scenarios: their names and texts (format: docs/scenarios.md). Each
// text lives in its own file, builtin_scenario_<name>.cpp; figures per scenario (route lengths,
// durations, a priori differences) are in docs/scenarios.md.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "builtin_scenario_texts.hpp"
#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

struct Builtin {
  std::string_view name;
  std::string_view (*text)();
};

constexpr std::array<Builtin, 3> kBuiltins{{
    {"loop170", &detail::Loop170ScenarioText},
    {"office", &detail::OfficeScenarioText},
    {"team", &detail::TeamScenarioText},
}};

}  // namespace

std::vector<std::string> BuiltinScenarioNames() {
  std::vector<std::string> names;
  for (const Builtin& builtin : kBuiltins) names.emplace_back(builtin.name);
  return names;
}

std::optional<std::string_view> BuiltinScenarioText(std::string_view name) {
  for (const Builtin& builtin : kBuiltins) {
    if (builtin.name == name) return builtin.text();
  }
  return std::nullopt;
}

}  // namespace pena::sim
