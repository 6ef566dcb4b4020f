#pragma once
// The local grid of an online run (paper section 3): a fixed window that moves with the entity and
// is handed to the line extraction whenever the entity nears its edge.

#include <Eigen/Core>

#include "pena/geometry/pose2.hpp"
#include "pena/grid/grid_image.hpp"
#include "pena/grid/grid_options.hpp"
#include "pena/grid/log_odds_cells.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::grid {

// Size of the moving window.
struct LocalGridOptions {
  GridOptions grid;
  double size_m = 20.0;        // side of the square window
  double edge_margin_m = 4.0;  // NeedsRecentre fires when the entity is this close to an edge
};

// A square window of world cells (same anchoring as OccupancyGrid). Beams reaching beyond the
// window are cut at its edge.
class LocalGrid {
 public:
  // Centres the window on `centre_m` (world, metres). Throws std::invalid_argument naming the
  // field for invalid options.
  LocalGrid(const LocalGridOptions& options, const Eigen::Vector2d& centre_m);

  // Integrates one scan; returns false, leaving the grid unchanged, for a non-finite pose.
  bool Insert(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser);

  // True when the entity is within edge_margin_m of the window's edge, or outside it.
  bool NeedsRecentre(const geometry::Pose2& world_from_entity) const;
  // Returns the window as it is, then recentres it on the entity; cells in both the old and the
  // new window keep their values, the rest start unknown. A non-finite or absurdly distant pose
  // leaves the window where it is.
  GridImage Recentre(const geometry::Pose2& world_from_entity);

  // Log-odds of a world cell; 0 outside the window.
  double LogOdds(const Eigen::Vector2i& cell) const { return cells_.LogOdds(cell); }
  // The window as an image (0 free, 255 occupied, 128 unknown).
  GridImage ToImage() const { return cells_.ToImage(options_.grid.resolution_m); }
  // Lowest world cell of the window and its side in cells.
  const Eigen::Vector2i& min_cell() const { return cells_.min_cell(); }
  int size_cells() const { return size_cells_; }
  const LocalGridOptions& options() const { return options_; }

 private:
  Eigen::Vector2i MinCellCentredOn(const Eigen::Vector2d& centre_m) const;

  LocalGridOptions options_;
  int size_cells_ = 0;
  LogOddsCells cells_;
};

}  // namespace pena::grid
