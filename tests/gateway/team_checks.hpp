#pragma once
// What the gateway's team runs check (test helper): the far side holds the team's maps, and the
// percentiles of pose ages.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "pena/gateway/domain_side.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/line_map/map_delta.hpp"

namespace pena::gateway::testing {

// The `fraction` quantile of `values` (linear rank, no interpolation); 0 for an empty sample.
inline double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1))];
}

// True when `far` holds every map of `team`, segment for segment.
inline bool MapsEqual(const SyntheticTeam& team, const InMemoryDomain& far) {
  for (const auto& [map_id, map] : team.maps()) {
    const auto found = far.maps().find(map_id);
    if (found == far.maps().end() || !line_map::SameMap(found->second.Snapshot(), map.Snapshot())) {
      return false;
    }
  }
  return true;
}

}  // namespace pena::gateway::testing
