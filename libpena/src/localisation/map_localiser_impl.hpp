#pragma once
// MapLocaliser's state and round steps, shared by map_localiser.cpp (options, the round and its
// conclusion, the public calls) and map_localiser_search.cpp (one search against the plan,
// its judgement, re-casting and the search along a corridor). Internal to libpena.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "pena/localisation/map_localiser.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {
namespace internal {

// What one search found: the correction (weak direction dropped where the scan does not
// constrain it), the weak translation direction of the refinement (body frame), and whether the
// search's best grid pose lies inside its window, not on its edge (only such an optimum is
// re-judged: one on the edge was not searched around, and re-casting there chains corrections
// beyond the window along a corridor).
struct Found {
  geometry::Pose2 correction;
  Eigen::Vector2d weak = Eigen::Vector2d::UnitX();
  bool interior = false;
  bool interior_xy = false;  // the same in x and y only (require_interior)
};

}  // namespace internal

struct MapLocaliser::Impl {
  MapLocaliserOptions options;
  VirtualScanner scanner;
  PlanAdaptation adaptation;
  geometry::Pose2 map_from_odom;
  MapStatus status = MapStatus::kUnknown;
  scan_matching::SearchWindow window;
  int failures = 0;
  double distance_m = 0.0;
  std::optional<geometry::Pose2> last_odom;
  // The pose on the plan at the last scan (the output).
  geometry::Pose2 pose;
  bool relocalised = false;  // Relocalise was called: the next round says so

  // Real returns in the body (laser) frame within the usable range band.
  scan_matching::Points2 RealPoints(const sensors::LaserScan& scan) const {
    scan_matching::Points2 points = scan_matching::ScanToPoints(scan, options.min_range_m);
    std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > options.max_range_m; });
    return points;
  }

  // The plan seen from `map_from_body` by the same laser, oversampled, in the body frame.
  scan_matching::Points2 VirtualPoints(const sensors::LaserScan& scan,
                                       const geometry::Pose2& map_from_body) const {
    if (scan.ranges_m.empty()) return {};
    sensors::LaserGeometry geometry = scan.geometry;
    geometry.angle_increment_rad /= options.oversample;
    geometry.max_range_m = std::min(options.max_range_m, scan.geometry.max_range_m > 0.0
                                                             ? scan.geometry.max_range_m
                                                             : options.max_range_m);
    const std::size_t beams = (scan.ranges_m.size() - 1) * static_cast<std::size_t>(options.oversample) + 1;
    return scan_matching::ScanToPoints(scanner.Scan(map_from_body, geometry, beams), 0.0);
  }

  void Accumulate(const geometry::Pose2& odom_from_body) {
    if (last_odom) {
      distance_m += std::hypot(odom_from_body.x_m - last_odom->x_m, odom_from_body.y_m - last_odom->y_m);
    }
    last_odom = odom_from_body;
  }

  // `on_prior`: the odometry took this pose, or a direction of it, from its motion prior.
  MapCorrection Round(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body, bool on_prior);
  // One search against the plan seen from `map_from_body` in `searched`; fills the round's
  // figures and acceptance, returns the correction it found (weak direction dropped where the
  // scan does not constrain it), also when rejected. nullopt: the plan is not in sight.
  std::optional<internal::Found> Search(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                              const geometry::Pose2& map_from_body,
                              const scan_matching::SearchWindow& searched, MapCorrection& round) const;
  // The round judged again from where `correction` puts the entity (see recast_min_m).
  MapCorrection Recast(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                       const MapCorrection& round, const geometry::Pose2& correction) const;
  // A degenerate round: the places along the weak direction, each judged from where it is.
  std::optional<MapCorrection> AlongSearch(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                           const MapCorrection& round, const internal::Found& found) const;
  internal::Found Judge(const scan_matching::MatchResult& match, const scan_matching::CorrelationScanMatcher& matcher,
              const scan_matching::Points2& real, const scan_matching::SearchWindow& searched,
              MapCorrection& round) const;
  bool NeedsRecast(const geometry::Pose2& correction) const {
    return std::hypot(correction.x_m, correction.y_m) >= options.recast_min_m ||
           std::abs(correction.theta_rad) >= options.recast_min_rad;
  }
  void Conclude(const geometry::Pose2& odom_from_body, MapCorrection& round);
  // An accepted round's returns (body frame) measure the plan's walls (plan_adaptation).
  void Learn(const scan_matching::Points2& real, const MapCorrection& round, double walked_m);
  // Moves an accepted round's corrected pose back where the plan's free wall ends agree it is.
  void CheckEnds(const scan_matching::Points2& real, MapCorrection& round) const;
  // A re-acquisition on a round its scan does not pin down in every direction (reacquire_pinned).
  bool WeakReacquisition(const MapCorrection& round) const;
};

}  // namespace pena::localisation
