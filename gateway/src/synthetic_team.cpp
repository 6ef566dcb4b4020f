#include "pena/gateway/synthetic_team.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pena::gateway {

SyntheticTeam::SyntheticTeam(SyntheticTeamOptions options)
    : options_(options), random_(options.seed) {
  if (options_.entities < 1) throw std::invalid_argument("team.entities must be >= 1");
  if (!(options_.pose_rate_hz > 0.0)) throw std::invalid_argument("team.pose_rate_hz must be > 0 Hz");
  if (!(options_.map_period_s > 0.0)) throw std::invalid_argument("team.map_period_s must be > 0 s");
  if (!(options_.area_m > 1.0)) throw std::invalid_argument("team.area_m must be > 1 m");
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < options_.entities; ++i) {
    Walker walker;
    walker.name = "ff" + std::to_string(i + 1);
    walker.phase_rad = 2.0 * std::numbers::pi * i / options_.entities;
    // Staggered starts, so the entities do not all publish in the same instant.
    walker.next_pose_s = options_.start_s + unit(random_) / options_.pose_rate_hz;
    walker.next_map_s = options_.start_s + unit(random_) * options_.map_period_s;
    walker.next_alarm_s = options_.alarm_period_s > 0.0
                              ? options_.start_s + (0.5 + unit(random_)) * options_.alarm_period_s
                              : std::numeric_limits<double>::infinity();
    maps_.emplace(walker.name, line_map::LineMap());
    walkers_.push_back(walker);
  }
}

// A slow loop around the building (about 1 m/s), different per entity.
geometry::Pose2 SyntheticTeam::PoseAt(const Walker& walker, double t_s) const {
  const double radius_m = 0.35 * options_.area_m;
  const double angle = walker.phase_rad + (t_s - options_.start_s) / radius_m;
  const double half = 0.5 * options_.area_m;
  return {half + radius_m * std::cos(angle), half + radius_m * std::sin(angle),
          geometry::NormalizeAngle(angle + 0.5 * std::numbers::pi)};
}

// Walls near the walker on a 2 m grid (axis-aligned, a little noise): revisits merge.
line_map::MapDelta SyntheticTeam::Integrate(const Walker& walker, double t_s) {
  const geometry::Pose2 pose = PoseAt(walker, t_s);
  std::uniform_real_distribution<double> offset(-6.0, 6.0);
  std::uniform_real_distribution<double> length(1.0, 4.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<line_map::LineSegment> fresh;
  for (int i = 0; i < options_.walls_per_update; ++i) {
    line_map::LineSegment wall;
    const double x = 2.0 * std::round((pose.x_m + offset(random_)) / 2.0);
    const double y = 2.0 * std::round((pose.y_m + offset(random_)) / 2.0);
    const bool horizontal = (i % 2) == 0;
    const double l = length(random_);
    wall.segment.start_m = {x + noise(random_), y + noise(random_)};
    wall.segment.end_m = horizontal ? Eigen::Vector2d(x + l, y + noise(random_))
                                    : Eigen::Vector2d(x + noise(random_), y + l);
    wall.support_cells = std::round(l / 0.05);
    wall.observations = 3.0 * wall.support_cells;
    wall.rms_error_m = 0.01;
    fresh.push_back(wall);
  }
  return maps_.at(walker.name).Integrate(fresh, walker.name);
}

std::vector<DomainItem> SyntheticTeam::Advance(double now_s) {
  std::vector<DomainItem> items;
  for (Walker& walker : walkers_) {
    for (; walker.next_pose_s <= now_s; walker.next_pose_s += 1.0 / options_.pose_rate_hz) {
      items.push_back(PoseUpdate{walker.name, PoseAt(walker, walker.next_pose_s), walker.next_pose_s});
    }
    for (; walker.next_alarm_s <= now_s; walker.next_alarm_s += options_.alarm_period_s) {
      const geometry::Pose2 pose = PoseAt(walker, walker.next_alarm_s);
      items.push_back(Annotation{true, walker.name, ++alarms_, pose.x_m, pose.y_m,
                                 walker.next_alarm_s, "no motion for 30 s"});
    }
    for (; walker.next_map_s <= now_s && walker.next_map_s <= options_.map_until_s;
         walker.next_map_s += options_.map_period_s) {
      line_map::MapDelta delta = Integrate(walker, walker.next_map_s);
      if (delta.empty()) continue;
      last_map_change_s_ = walker.next_map_s;
      items.push_back(MapChange{walker.name, std::move(delta), false});
    }
  }
  return items;
}

}  // namespace pena::gateway
