#include "pena/grid/scan_rays.hpp"

#include <algorithm>
#include <cmath>

namespace pena::grid {
namespace {

// Cells stay well inside int so Bresenham's error terms (2 * delta) cannot overflow.
constexpr double kMaxCellIndex = 1 << 28;

bool IsFinite(const geometry::Pose2& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.theta_rad);
}

void Extend(ScanRays& rays, const Eigen::Vector2i& cell) {
  rays.min_cell = rays.min_cell.cwiseMin(cell);
  rays.max_cell = rays.max_cell.cwiseMax(cell);
}

}  // namespace

Eigen::Vector2i WorldCell(const Eigen::Vector2d& point_m, double resolution_m) {
  return {static_cast<int>(std::floor(point_m.x() / resolution_m)),
          static_cast<int>(std::floor(point_m.y() / resolution_m))};
}

std::optional<ScanRays> CastScan(const sensors::LaserScan& scan,
                                 const geometry::Pose2& world_from_laser,
                                 const GridOptions& options) {
  if (!IsFinite(world_from_laser)) return std::nullopt;
  // The farthest any beam end can be: bounds the cell indices before converting to int.
  const double reach_m = std::max(options.max_range_m, options.no_return_clear_m);
  const double limit_m = kMaxCellIndex * options.resolution_m - reach_m;
  if (std::abs(world_from_laser.x_m) > limit_m || std::abs(world_from_laser.y_m) > limit_m) {
    return std::nullopt;
  }
  ScanRays rays;
  const Eigen::Vector2d origin_m(world_from_laser.x_m, world_from_laser.y_m);
  rays.origin_cell = WorldCell(origin_m, options.resolution_m);
  rays.min_cell = rays.max_cell = rays.origin_cell;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range_m = scan.ranges_m[i];
    if (std::isnan(range_m) || range_m <= 0.0) continue;
    const bool hit = scan.IsReturn(i) && range_m < options.max_range_m;
    const double length_m = hit ? range_m : std::min(range_m, options.no_return_clear_m);
    if (length_m <= 0.0) continue;  // clearing disabled
    const double angle_rad = world_from_laser.theta_rad + scan.BeamAngle(i);
    const Eigen::Vector2d end_m =
        origin_m + length_m * Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad));
    if (!end_m.allFinite()) continue;  // a corrupt beam geometry, not a crash
    const Eigen::Vector2i end_cell = WorldCell(end_m, options.resolution_m);
    (hit ? rays.hit_cells : rays.clear_cells).push_back(end_cell);
    Extend(rays, end_cell);
  }
  return rays;
}

}  // namespace pena::grid
