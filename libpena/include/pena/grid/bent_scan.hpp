#pragma once
// Bent scans (docs/grid.md, "Bent scans"): a walker who bends over (or looks up) tilts the
// laser's plane. Its returns from the floor (ceiling) then lie on a line h / sin(tilt) from the
// laser (it reports slant ranges), and every wall it sees is drawn at the slant range
// d / cos(elevation), up to 6 % of the range behind the wall, where no later beam from that side
// can clear it. Such a scan gives itself away against a grid of the same walk: many of its
// returns end in cells that other scans saw through, all on one line.

#include <Eigen/Core>
#include <optional>

#include "pena/geometry/pose2.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::grid {

struct BentScanOptions {
  double free_log_odds = -1.0;    // a return ending in a cell at or below this hit free space
  int min_free_ends = 10;         // fewer such returns: not judged (a person, a door that moved)
  double min_ahead_m = 1.0;       // the line they lie on must be [min, max] from the laser:
  double max_ahead_m = 8.5;       // 8.5 m is a tilt above 8 deg at 1.2 m (walls >= 1 % too far)
  double max_spread = 0.1;        // their median distance to that line / its distance
  // Level: the laser's height above the floor (a firefighter's chest, as the odometry's
  // tilt_laser_height_m), which turns the floor line's distance into the tilt.
  double laser_height_m = 1.2;
  double floor_band = 0.07;  // returns within this share of the floor line's distance: floor
};

// Where a tilted laser plane meets the floor, in the laser's frame: the line's unit normal
// (pointing away from the laser) and its distance.
struct FloorLine {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double distance_m = 0.0;
};

// Throws std::invalid_argument naming the field.
void ValidateBentScanOptions(const BentScanOptions& options);

// Judges scans against a grid of the same walk and levels the bent ones. The options are checked
// once, by the constructor.
class BentScanLeveller {
 public:
  // Throws std::invalid_argument naming the field (ValidateBentScanOptions).
  explicit BentScanLeveller(const BentScanOptions& options = {});

  // The line along which the scan met the floor or ceiling when `reference` (a grid of the same
  // walk) shows it bent, else nullopt. world_from_laser: the laser's pose in the grid's frame.
  std::optional<FloorLine> FloorLineOf(const OccupancyGrid& reference,
                                       const sensors::LaserScan& scan,
                                       const geometry::Pose2& world_from_laser) const;

  // The scan as a level laser would have measured it: ranges reduced to their horizontal part,
  // returns at the floor line set to NaN (neither hit nor free space).
  sensors::LaserScan Level(const sensors::LaserScan& scan, const FloorLine& floor) const;

  const BentScanOptions& options() const { return options_; }

 private:
  BentScanOptions options_;
};

}  // namespace pena::grid
