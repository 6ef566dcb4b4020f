#pragma once
// The storage shared by the global and the local grid: a dense block of log-odds cells with the
// per-scan Bayesian update (Elfes 1990) along Bresenham rays.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "pena/grid/grid_image.hpp"
#include "pena/grid/grid_options.hpp"
#include "pena/grid/scan_rays.hpp"

namespace pena::grid {

// Cells [min_cell, min_cell + (width, height)) of the world grid, each a clamped log-odds value.
class LogOddsCells {
 public:
  LogOddsCells() = default;  // empty bounds
  // All cells unknown (log-odds 0). Throws std::invalid_argument for a negative size.
  LogOddsCells(const Eigen::Vector2i& min_cell, int width, int height);

  // True when a world cell lies inside the bounds.
  bool Contains(const Eigen::Vector2i& cell) const {
    return cell.x() >= min_cell_.x() && cell.y() >= min_cell_.y() &&
           cell.x() - min_cell_.x() < width_ && cell.y() - min_cell_.y() < height_;
  }
  // Log-odds of a world cell; 0 (unknown) outside the bounds.
  double LogOdds(const Eigen::Vector2i& cell) const;

  // Moves the bounds, keeping the values of cells inside both the old and the new bounds.
  void Reframe(const Eigen::Vector2i& min_cell, int width, int height);

  // Applies one scan: every cell is updated at most once, a hit (occupied) taking precedence over
  // a miss (free). Cells outside the bounds are skipped.
  void Insert(const ScanRays& rays, const GridOptions& options);

  // The cells as an image (0 free, 255 occupied, 128 unknown) with its world origin, plus each
  // cell's hit count and first and last hitting scan.
  GridImage ToImage(double resolution_m) const;

  const Eigen::Vector2i& min_cell() const { return min_cell_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::size_t Index(int local_x, int local_y) const;
  void ApplyHits(const ScanRays& rays, float hit, float max_value);
  void CastFree(const Eigen::Vector2i& from, const Eigen::Vector2i& to, bool include_end,
                float miss, float min_value);
  void AdvanceStamp();

  Eigen::Vector2i min_cell_ = Eigen::Vector2i::Zero();
  int width_ = 0;
  int height_ = 0;
  std::vector<float> log_odds_;
  // Per cell, the stamp of the last scan that updated it: 2 * scan for a miss, 2 * scan + 1 for
  // a hit, so one comparison tells whether the current scan already touched it.
  std::vector<std::uint32_t> stamps_;
  std::vector<std::uint16_t> hit_counts_;  // laser hits per cell, saturating
  // scan_ of the first and of the last scan that hit the cell (0: none).
  std::vector<std::int32_t> first_hit_scans_;
  std::vector<std::int32_t> last_hit_scans_;
  std::uint32_t scan_ = 0;
};

}  // namespace pena::grid
