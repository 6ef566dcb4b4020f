#pragma once
// The global occupancy grid of an offline run: grows as scans reach new ground.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/grid/grid_image.hpp"
#include "pena/grid/grid_options.hpp"
#include "pena/grid/log_odds_cells.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::grid {

// A world-frame log-odds grid anchored at the world origin: cell (i, j) covers
// x in [i * res, (i + 1) * res) and y in [j * res, (j + 1) * res). It grows by whole blocks so
// every beam of an inserted scan lies inside it.
class OccupancyGrid {
 public:
  // Throws std::invalid_argument for invalid options (see ValidateGridOptions).
  explicit OccupancyGrid(const GridOptions& options = {});

  // Integrates one scan taken at `world_from_laser`. Returns false, leaving the grid unchanged,
  // when the pose is not finite or the grid would have to exceed options.max_size_m.
  bool Insert(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser);

  // Returns of a scan that end in cells this grid knows to be free (log-odds <= free_log_odds),
  // in the laser's frame. A walker bent over (or looking up) hits the floor (ceiling) where other
  // scans saw through, along one line (docs/grid.md, "Bent scans").
  std::vector<Eigen::Vector2d> FreeEnds(const sensors::LaserScan& scan,
                                        const geometry::Pose2& world_from_laser,
                                        double free_log_odds) const;

  // The cell containing a world point (may lie outside the current bounds).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& point_m) const;
  // Log-odds of a world cell; 0 (unknown) outside the bounds.
  double LogOdds(const Eigen::Vector2i& cell) const { return cells_.LogOdds(cell); }
  // Probability of occupancy of a world cell; 0.5 outside the bounds.
  double Probability(const Eigen::Vector2i& cell) const;

  // The whole grid as an image (0 free, 255 occupied, 128 unknown); empty before the first scan.
  GridImage ToImage() const { return cells_.ToImage(options_.resolution_m); }

  // Lowest world cell of the bounds and the size in cells.
  const Eigen::Vector2i& min_cell() const { return cells_.min_cell(); }
  int width() const { return cells_.width(); }
  int height() const { return cells_.height(); }
  std::size_t scans_inserted() const { return scans_inserted_; }
  const GridOptions& options() const { return options_; }

 private:
  GridOptions options_;
  LogOddsCells cells_;
  std::size_t scans_inserted_ = 0;
};

}  // namespace pena::grid
