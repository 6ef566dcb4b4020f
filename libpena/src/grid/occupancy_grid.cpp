#include "pena/grid/occupancy_grid.hpp"

#include <cmath>

#include "pena/grid/scan_rays.hpp"

namespace pena::grid {
namespace {

// Growth in blocks of this many cells per side (3.2 m at 5 cm): few reallocations on a walk.
constexpr int kBlockCells = 64;

int FloorToBlock(int cell) {
  return (cell >= 0 ? cell : cell - (kBlockCells - 1)) / kBlockCells * kBlockCells;
}

}  // namespace

OccupancyGrid::OccupancyGrid(const GridOptions& options) : options_(options) {
  ValidateGridOptions(options_);
}

bool OccupancyGrid::Insert(const sensors::LaserScan& scan,
                           const geometry::Pose2& world_from_laser) {
  const std::optional<ScanRays> rays = CastScan(scan, world_from_laser, options_);
  if (!rays) return false;
  const Eigen::Vector2i old_low = cells_.min_cell();
  const Eigen::Vector2i old_high = old_low + Eigen::Vector2i(cells_.width(), cells_.height());
  const bool empty = cells_.width() == 0;
  if (empty || !cells_.Contains(rays->min_cell) || !cells_.Contains(rays->max_cell)) {
    Eigen::Vector2i low = empty ? rays->min_cell : old_low.cwiseMin(rays->min_cell);
    Eigen::Vector2i high = empty ? Eigen::Vector2i(rays->max_cell + Eigen::Vector2i::Ones())
                                 : old_high.cwiseMax(rays->max_cell + Eigen::Vector2i::Ones());
    low = {FloorToBlock(low.x()), FloorToBlock(low.y())};
    high = {FloorToBlock(high.x() + kBlockCells - 1), FloorToBlock(high.y() + kBlockCells - 1)};
    const Eigen::Vector2i size = high - low;
    const double max_cells = options_.max_size_m / options_.resolution_m;
    if (size.x() > max_cells || size.y() > max_cells) return false;
    cells_.Reframe(low, size.x(), size.y());
  }
  cells_.Insert(*rays, options_);
  ++scans_inserted_;
  return true;
}

std::vector<Eigen::Vector2d> OccupancyGrid::FreeEnds(const sensors::LaserScan& scan,
                                                     const geometry::Pose2& world_from_laser,
                                                     double free_log_odds) const {
  std::vector<Eigen::Vector2d> ends_m;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range_m = scan.ranges_m[i];
    if (!scan.IsReturn(i) || !(range_m < options_.max_range_m)) continue;
    const double angle_rad = world_from_laser.theta_rad + scan.BeamAngle(i);
    const Eigen::Vector2d end_m(world_from_laser.x_m + range_m * std::cos(angle_rad),
                                world_from_laser.y_m + range_m * std::sin(angle_rad));
    if (!end_m.allFinite()) continue;
    if (cells_.LogOdds(CellOf(end_m)) <= free_log_odds) {
      ends_m.emplace_back(range_m * std::cos(scan.BeamAngle(i)),
                          range_m * std::sin(scan.BeamAngle(i)));
    }
  }
  return ends_m;
}

Eigen::Vector2i OccupancyGrid::CellOf(const Eigen::Vector2d& point_m) const {
  return WorldCell(point_m, options_.resolution_m);
}

double OccupancyGrid::Probability(const Eigen::Vector2i& cell) const {
  return ProbabilityFromLogOdds(LogOdds(cell));
}

}  // namespace pena::grid
