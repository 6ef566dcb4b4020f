#include "pena/scan_matching/point_set.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pena::scan_matching {
namespace {

// The mean of i mod interlace over beams i = 0 .. beams - 1 (> 0): the turns then add nothing
// on average. Whole sweeps of `interlace` beams contribute 0 + 1 + ... + (interlace - 1) each.
double MeanSweep(std::size_t beams, std::size_t interlace) {
  const std::size_t whole = beams / interlace;
  const std::size_t rest = beams % interlace;
  const std::size_t sum =
      whole * interlace * (interlace - 1) / 2 + (rest == 0 ? 0 : rest * (rest - 1) / 2);
  return static_cast<double>(sum) / static_cast<double>(beams);
}

}  // namespace

Points2 ScanToPoints(const sensors::LaserScan& scan, double min_range_m) {
  return ScanToPointsAtMidSweep(scan, min_range_m, 0.0);
}

Points2 ScanToPointsAtMidSweep(const sensors::LaserScan& scan, double min_range_m,
                               double rotation_rate_rad_s) {
  const std::size_t beams = scan.ranges_m.size();
  // Beam i is taken at i / (beams - 1) * sweep_s plus (i mod interlace) mirror turns after the
  // first beam; by then the laser frame has turned by rate * that, so its return lies that much
  // further round in the frame of the mean beam time. No turn (or no sweep) adds exactly 0.
  const double turn_per_beam_rad =
      beams < 2 ? 0.0
                : rotation_rate_rad_s * scan.geometry.sweep_s / static_cast<double>(beams - 1);
  const double middle = beams < 2 ? 0.0 : 0.5 * static_cast<double>(beams - 1);
  const auto interlace = static_cast<std::size_t>(std::max(scan.geometry.interlace, 1));
  const double field_rad =
      beams < 2 ? 0.0
                : std::abs(scan.geometry.angle_increment_rad) * static_cast<double>(beams - 1);
  const double turn_per_mirror_turn_rad =
      interlace < 2 || !(field_rad > 0.0)
          ? 0.0
          : rotation_rate_rad_s * scan.geometry.sweep_s * 2.0 * std::numbers::pi / field_rad;
  const double mean_sweep = turn_per_mirror_turn_rad == 0.0 ? 0.0 : MeanSweep(beams, interlace);
  Points2 points;
  points.reserve(beams);
  for (std::size_t i = 0; i < beams; ++i) {
    if (!scan.IsReturn(i) || scan.ranges_m[i] < min_range_m) continue;
    const double sweep = static_cast<double>(i % interlace);
    const double angle = scan.BeamAngle(i) + turn_per_beam_rad * (static_cast<double>(i) - middle) +
                         turn_per_mirror_turn_rad * (sweep - mean_sweep);
    const double range = scan.ranges_m[i];
    points.emplace_back(range * std::cos(angle), range * std::sin(angle));
  }
  return points;
}

Points2 TransformPoints(const geometry::Pose2& a_from_b, const Points2& points_b) {
  Points2 points_a;
  points_a.reserve(points_b.size());
  const geometry::PointTransform transform(a_from_b);
  for (const auto& point : points_b) points_a.push_back(transform(point));
  return points_a;
}

}  // namespace pena::scan_matching
