#pragma once
// A synthetic rescue team for link tests and experiments without DDS: entities walking through a
// building, each publishing poses, occasional alarms, and line-map deltas from a real LineMap fed
// with wall segments near its path (so deltas have the sizes and merges of real ones).

#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "pena/gateway/link_items.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::gateway {

// What the team produces; validated by SyntheticTeam's constructor.
struct SyntheticTeamOptions {
  int entities = 4;                      // named ff1, ff2, ...
  double pose_rate_hz = 2.0;             // poses per entity per second
  double map_period_s = 2.0;             // each entity integrates new walls this often
  int walls_per_update = 4;              // fresh wall segments per integration
  double alarm_period_s = 30.0;          // each entity raises an alarm this often (0: never)
  double map_until_s = std::numeric_limits<double>::infinity();  // no map changes after this
  double area_m = 60.0;                  // side of the square building
  std::uint64_t seed = 7;
  double start_s = 0.0;                  // clock value at which the team starts (stamps follow it)
};

class SyntheticTeam {
 public:
  // Throws std::invalid_argument naming the field and unit for a bad option.
  explicit SyntheticTeam(SyntheticTeamOptions options);
  // Everything the team produced in (last call, now_s], oldest first.
  std::vector<DomainItem> Advance(double now_s);
  // The entities' own maps (the near side's truth), by map id (= entity name).
  const std::map<std::string, line_map::LineMap>& maps() const { return maps_; }
  // Time of the last map change (-inf if none yet).
  double last_map_change_s() const { return last_map_change_s_; }
  // Alarms raised so far.
  std::size_t alarms() const { return alarms_; }

 private:
  struct Walker {
    std::string name;
    double phase_rad = 0.0;
    double next_pose_s = 0.0;
    double next_map_s = 0.0;
    double next_alarm_s = 0.0;
  };
  geometry::Pose2 PoseAt(const Walker& walker, double t_s) const;
  line_map::MapDelta Integrate(const Walker& walker, double t_s);

  SyntheticTeamOptions options_;
  std::mt19937_64 random_;
  std::vector<Walker> walkers_;
  std::map<std::string, line_map::LineMap> maps_;
  double last_map_change_s_ = -std::numeric_limits<double>::infinity();
  std::size_t alarms_ = 0;
};

}  // namespace pena::gateway
