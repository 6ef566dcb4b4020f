#pragma once
// Virtual scans (paper section 4.2): the range of each beam is the distance to the nearest
// intersection of the beam with the plan's segments. A uniform grid indexes the segments and each
// ray walks its cells in order (Amanatides & Woo 1987), so a scan costs the cells the beams cross,
// not the size of the plan.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::localisation {

// Options of the spatial index. Validated by the constructor.
struct VirtualScannerOptions {
  double cell_size_m = 1.0;  // side of a grid cell of the segment index
};

// Ray casting against one plan (map frame, metres). Holds a copy of the segments. Thread-safe
// after construction (all queries are const).
class VirtualScanner {
 public:
  // Throws std::invalid_argument if cell_size_m is not > 0 or the plan would need more than
  // 2^26 cells at that size.
  explicit VirtualScanner(std::vector<geometry::Segment2> segments,
                          const VirtualScannerOptions& options = {});

  // Distance in metres along the ray (origin, unit direction; map frame) to the nearest segment,
  // or +infinity if none is nearer than max_range_m.
  double CastRay(const Eigen::Vector2d& origin_m, const Eigen::Vector2d& direction_unit,
                 double max_range_m) const;

  // Ranges of `beams` beams of `geometry` from the laser at `map_from_laser` into `ranges_m`
  // (resized); a beam that hits nothing within geometry.max_range_m is sensors::kNoReturn.
  void CastScan(const geometry::Pose2& map_from_laser, const sensors::LaserGeometry& geometry,
                std::size_t beams, std::vector<float>& ranges_m) const;

  // The same as a LaserScan stamped `stamp_s` (no odometry or logged pose).
  sensors::LaserScan Scan(const geometry::Pose2& map_from_laser,
                          const sensors::LaserGeometry& geometry, std::size_t beams,
                          double stamp_s = 0.0) const;

  const std::vector<geometry::Segment2>& segments() const { return segments_; }
  // Corners of the plan's bounding box (map frame, metres); both zero for an empty plan.
  const Eigen::Vector2d& min_m() const { return min_m_; }
  const Eigen::Vector2d& max_m() const { return max_m_; }

 private:
  // A segment prepared for the intersection test: start point and edge vector.
  struct Edge {
    double sx, sy, ex, ey;
  };
  void BuildIndex();
  double NearestInCell(std::size_t cell, double ox, double oy, double dx, double dy,
                       double best) const;

  std::vector<geometry::Segment2> segments_;
  std::vector<Edge> edges_;
  double cell_size_m_;
  Eigen::Vector2d min_m_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m_ = Eigen::Vector2d::Zero();
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint32_t> cell_start_;   // CSR: segments of cell c are
  std::vector<std::uint32_t> cell_items_;   // cell_items_[cell_start_[c] .. cell_start_[c + 1])
};

}  // namespace pena::localisation
