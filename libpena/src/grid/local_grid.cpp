#include "pena/grid/local_grid.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "pena/grid/scan_rays.hpp"

namespace pena::grid {
namespace {

// Keeps the window's cell indices far inside int (see scan_rays.cpp).
constexpr double kMaxCentreCell = 1 << 27;

bool IsUsableCentre(const Eigen::Vector2d& centre_m, double resolution_m) {
  return centre_m.allFinite() && centre_m.cwiseAbs().maxCoeff() / resolution_m < kMaxCentreCell;
}

void Validate(const LocalGridOptions& options) {
  ValidateGridOptions(options.grid);
  std::ostringstream message;
  if (!(std::isfinite(options.size_m) && options.size_m >= options.grid.resolution_m &&
        options.size_m <= options.grid.max_size_m)) {
    message << "local_grid.size_m must be between grid.resolution_m and grid.max_size_m (m), got "
            << options.size_m;
  } else if (!(std::isfinite(options.edge_margin_m) && options.edge_margin_m >= 0.0 &&
               options.edge_margin_m < options.size_m / 2.0)) {
    message << "local_grid.edge_margin_m must be >= 0 m and < size_m / 2, got "
            << options.edge_margin_m;
  } else {
    return;
  }
  throw std::invalid_argument(message.str());
}

}  // namespace

LocalGrid::LocalGrid(const LocalGridOptions& options, const Eigen::Vector2d& centre_m)
    : options_(options) {
  Validate(options_);
  if (!IsUsableCentre(centre_m, options_.grid.resolution_m)) {
    throw std::invalid_argument("local grid centre must be finite and within 2^27 cells of 0 (m)");
  }
  size_cells_ = static_cast<int>(std::ceil(options_.size_m / options_.grid.resolution_m));
  cells_ = LogOddsCells(MinCellCentredOn(centre_m), size_cells_, size_cells_);
}

bool LocalGrid::Insert(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser) {
  const std::optional<ScanRays> rays = CastScan(scan, world_from_laser, options_.grid);
  if (!rays) return false;
  cells_.Insert(*rays, options_.grid);  // rays are cut at the window's edge
  return true;
}

bool LocalGrid::NeedsRecentre(const geometry::Pose2& world_from_entity) const {
  const double resolution_m = options_.grid.resolution_m;
  const Eigen::Vector2d low_m = cells_.min_cell().cast<double>() * resolution_m;
  const Eigen::Vector2d high_m = low_m + Eigen::Vector2d::Constant(size_cells_ * resolution_m);
  const Eigen::Vector2d entity_m(world_from_entity.x_m, world_from_entity.y_m);
  const double margin_m = options_.edge_margin_m;
  // Written so that a NaN position also asks for a recentre (every comparison false).
  const bool inside = entity_m.x() - low_m.x() > margin_m && high_m.x() - entity_m.x() > margin_m &&
                      entity_m.y() - low_m.y() > margin_m && high_m.y() - entity_m.y() > margin_m;
  return !inside;
}

GridImage LocalGrid::Recentre(const geometry::Pose2& world_from_entity) {
  GridImage before = cells_.ToImage(options_.grid.resolution_m);
  const Eigen::Vector2d centre_m(world_from_entity.x_m, world_from_entity.y_m);
  if (IsUsableCentre(centre_m, options_.grid.resolution_m))
    cells_.Reframe(MinCellCentredOn(centre_m), size_cells_, size_cells_);
  return before;
}

Eigen::Vector2i LocalGrid::MinCellCentredOn(const Eigen::Vector2d& centre_m) const {
  return WorldCell(centre_m, options_.grid.resolution_m) -
         Eigen::Vector2i::Constant(size_cells_ / 2);
}

}  // namespace pena::grid
