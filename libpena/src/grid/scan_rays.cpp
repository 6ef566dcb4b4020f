#include "pena/grid/scan_rays.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

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

enum class BeamKind { kIgnored, kHit, kClear };

// One beam in the world frame: where it ends and whether that end is a return.
struct Beam {
  BeamKind kind = BeamKind::kIgnored;
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
};

// How far this scan demonstrably saw: its farthest return (trusted for mapping or not). In smoke
// the laser sees only a few metres and reports no-returns beyond; such a no-return says nothing
// past that reach, and clearing further would erase the walls just behind the smoke's range.
double Reach(const sensors::LaserScan& scan) {
  double reach_m = 0.0;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (scan.IsReturn(i)) reach_m = std::max(reach_m, static_cast<double>(scan.ranges_m[i]));
  }
  return reach_m;
}

std::vector<Beam> CastBeams(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser,
                            const GridOptions& options) {
  const Eigen::Vector2d origin_m(world_from_laser.x_m, world_from_laser.y_m);
  std::vector<Beam> beams(scan.ranges_m.size());
  const double clear_m = std::min(options.no_return_clear_m, Reach(scan));
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range_m = scan.ranges_m[i];
    if (std::isnan(range_m) || range_m <= 0.0) continue;
    const bool hit = scan.IsReturn(i) && range_m < options.max_range_m;
    const double length_m = hit ? range_m : std::min(range_m, clear_m);
    if (length_m <= 0.0) continue;  // clearing disabled
    const double angle_rad = world_from_laser.theta_rad + scan.BeamAngle(i);
    const Eigen::Vector2d direction(std::cos(angle_rad), std::sin(angle_rad));
    const Eigen::Vector2d end_m = origin_m + length_m * direction;
    if (!end_m.allFinite()) continue;  // a corrupt beam geometry, not a crash
    beams[i] = {hit ? BeamKind::kHit : BeamKind::kClear, end_m, direction};
  }
  return beams;
}

// How much of hit beam i, before its return, lies within surface_band_m of the surface it hit:
// band / sin(incidence), the surface's direction being the one to the nearer neighbouring
// return. At a grazing angle those cells are the wall itself (hit by other beams), and clearing
// them would erase the wall. Without a neighbouring return the surface is unknown: no skip.
double SurfaceSkip(const std::vector<Beam>& beams, std::size_t i, const Eigen::Vector2d& origin_m,
                   const GridOptions& options) {
  if (options.surface_band_m <= 0.0) return 0.0;
  const Beam& beam = beams[i];
  std::optional<Eigen::Vector2d> tangent;
  for (const std::size_t n : {i - 1, i + 1}) {  // i - 1 wraps for i = 0 and fails the bound
    if (n >= beams.size() || beams[n].kind != BeamKind::kHit) continue;
    const Eigen::Vector2d along = beams[n].end_m - beam.end_m;
    if (along.norm() > 0.0 && (!tangent || along.norm() < tangent->norm())) tangent = along;
  }
  if (!tangent) return 0.0;
  const double sin_incidence =
      std::abs(beam.direction.x() * tangent->y() - beam.direction.y() * tangent->x()) /
      tangent->norm();
  const double range_m = (beam.end_m - origin_m).norm();
  const double skip_m = options.surface_band_m / std::max(sin_incidence, 1e-6);
  return std::min({skip_m, options.max_surface_skip_m, range_m});
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
  const Eigen::Vector2d origin_m(world_from_laser.x_m, world_from_laser.y_m);
  const std::vector<Beam> beams = CastBeams(scan, world_from_laser, options);
  ScanRays rays;
  rays.origin_cell = WorldCell(origin_m, options.resolution_m);
  rays.min_cell = rays.max_cell = rays.origin_cell;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const Beam& beam = beams[i];
    if (beam.kind == BeamKind::kIgnored) continue;
    const Eigen::Vector2i end_cell = WorldCell(beam.end_m, options.resolution_m);
    Extend(rays, end_cell);
    if (beam.kind == BeamKind::kClear) {
      rays.clear_cells.push_back(end_cell);
      continue;
    }
    rays.hit_cells.push_back(end_cell);
    const double skip_m = SurfaceSkip(beams, i, origin_m, options);
    rays.free_end_cells.push_back(
        skip_m > 0.0 ? WorldCell(beam.end_m - skip_m * beam.direction, options.resolution_m)
                     : end_cell);
  }
  return rays;
}

}  // namespace pena::grid
