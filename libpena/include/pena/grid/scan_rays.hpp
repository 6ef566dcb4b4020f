#pragma once
// A laser scan cast into grid cells: where each beam starts and ends, and whether it ends on a
// return.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/grid/grid_options.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::grid {

// World cells (anchored at the world origin, side options.resolution_m) touched by one scan.
struct ScanRays {
  Eigen::Vector2i origin_cell = Eigen::Vector2i::Zero();  // the laser's cell
  std::vector<Eigen::Vector2i> hit_cells;    // cells of trusted returns: occupied, free before
  // Per hit cell, where the free part of its beam stops (this cell and the rest are not cleared):
  // the hit cell itself, or a cell before it when the beam grazes the surface it hit.
  std::vector<Eigen::Vector2i> free_end_cells;
  std::vector<Eigen::Vector2i> clear_cells;  // ends of no-return beams: free up to and including
  Eigen::Vector2i min_cell = Eigen::Vector2i::Zero();  // bounding box of all cells above
  Eigen::Vector2i max_cell = Eigen::Vector2i::Zero();
};

// The world cell containing a point.
Eigen::Vector2i WorldCell(const Eigen::Vector2d& point_m, double resolution_m);

// Casts a scan taken at `world_from_laser`. A beam is a return when scan.IsReturn(i) and its range
// is below options.max_range_m; other positive beams (+inf included) clear up to
// options.no_return_clear_m; NaN, zero and negative ranges are ignored. A return's free part
// stops options.surface_band_m / sin(incidence) before the hit (at most max_surface_skip_m), the
// surface's direction taken from the nearer neighbouring return (docs/grid.md, "Grazing beams").
// Returns nullopt when the pose is not finite or the cells would overflow int.
std::optional<ScanRays> CastScan(const sensors::LaserScan& scan,
                                 const geometry::Pose2& world_from_laser,
                                 const GridOptions& options);

}  // namespace pena::grid
