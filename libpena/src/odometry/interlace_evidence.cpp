#include "interlace_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pena/scan_matching/point_set.hpp"

namespace pena::odometry::internal {

std::optional<double> ContourRoughness(const sensors::LaserScan& scan,
                                       const sensors::LaserGeometry& geometry,
                                       double rotation_rate_rad_s, double min_range_m) {
  // Every beam becomes a point (no-returns at a placeholder range, flagged unusable) so that
  // point i is beam i and its neighbours are beam neighbours.
  sensors::LaserScan indexed = scan;
  indexed.geometry = geometry;
  indexed.geometry.max_range_m = std::numeric_limits<double>::infinity();
  const std::size_t beams = scan.ranges_m.size();
  std::vector<bool> usable(beams, false);
  for (std::size_t i = 0; i < beams; ++i) {
    usable[i] = scan.IsReturn(i) && scan.ranges_m[i] >= min_range_m;
    if (!usable[i]) indexed.ranges_m[i] = 1.0f;
  }
  const scan_matching::Points2 points =
      scan_matching::ScanToPointsAtMidSweep(indexed, 0.0, rotation_rate_rad_s);
  if (points.size() != beams) return std::nullopt;
  std::vector<double> distances;
  distances.reserve(beams);
  for (std::size_t i = 1; i + 1 < beams; ++i) {
    if (!usable[i - 1] || !usable[i] || !usable[i + 1]) continue;
    const Eigen::Vector2d chord = points[i + 1] - points[i - 1];
    const double length = chord.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector2d to_point = points[i] - points[i - 1];
    distances.push_back(std::abs(chord.x() * to_point.y() - chord.y() * to_point.x()) / length);
  }
  if (distances.size() < 10) return std::nullopt;
  const auto middle = distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  return *middle;
}

void InterlaceEvidence::Add(const sensors::LaserScan& scan, double rotation_rate_rad_s,
                            double min_range_m) {
  if (decided_ || scan.geometry.interlace < 2 || rotation_rate_rad_s == 0.0) return;
  sensors::LaserGeometry one_sweep = scan.geometry;
  one_sweep.interlace = 1;
  const std::optional<double> one = ContourRoughness(scan, one_sweep, rotation_rate_rad_s, min_range_m);
  const std::optional<double> configured =
      ContourRoughness(scan, scan.geometry, rotation_rate_rad_s, min_range_m);
  if (!one || !configured || !(*one > 0.0) || !(*configured > 0.0)) return;
  log_ratio_ += std::log(*one / *configured);
  const double bound = std::log(1.0 / kErrorRate);
  if (log_ratio_ >= bound) decided_ = scan.geometry.interlace;
  if (log_ratio_ <= -bound) decided_ = 1;
}

int InterlaceEvidence::Interlace(int configured) const { return decided_.value_or(configured); }

}  // namespace pena::odometry::internal
