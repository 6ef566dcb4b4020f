#pragma once
// Returns where an earlier scan saw through (issue 3): a body-worn laser pitched down by a bend
// hits the floor on a line across the corridor 3-9 m ahead (the paper's eq. 1), where the scans
// before the bend saw the corridor go on for 15-30 m. Such a line moves with the walker; matched,
// it reads as an end wall that keeps its distance and pulls the match back (office seed 1 at
// 158.5-160.5 s: 0.16-0.30 m a scan against the true motion, the truth as prior). A static wall
// is never inside space an earlier scan saw through; a floor or ceiling hit is.
//
// Each return, placed by the motion prior, is looked up in the earlier scans kept (their own
// poses and ranges): if one of them had its beams in that direction end farther away by more
// than the margin, the return is marked.

#include <deque>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/point_set.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::odometry::internal {

struct SeenThroughOptions {
  int history_scans = 16;       // earlier scans kept (4 s at 4 Hz: longer than most bends)
  double margin_m = 1.0;        // the earlier beam must end this much farther ...
  double margin_per_m = 0.1;    // ... plus this share of the return's range from it
  double min_range_m = 0.5;     // returns nearer an earlier scan than this are not tested
};

class SeenThroughPoints {
 public:
  explicit SeenThroughPoints(const SeenThroughOptions& options = {}) : options_(options) {}

  // For each of `points` (laser frame of a scan at world_from_laser): whether an earlier scan
  // saw through where it lies.
  std::vector<bool> Find(const scan_matching::Points2& points, const geometry::Pose2& world_from_laser) const;
  // Keeps `scan` (taken at world_from_laser) as an earlier scan for the next ones.
  void Remember(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser);

 private:
  struct View {
    geometry::Pose2 laser_from_world;
    sensors::LaserGeometry geometry;
    std::vector<float> ranges_m;
  };
  // How far `view` saw at the bearing of `point` (its own frame): the nearest return of the beam
  // and its two neighbours; negative when outside its field of view or none of them returned.
  static double SeenRange(const View& view, const Eigen::Vector2d& point);

  SeenThroughOptions options_;
  std::deque<View> views_;
};

}  // namespace pena::odometry::internal
