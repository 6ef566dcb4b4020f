#include "pena/localisation/virtual_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pena::localisation {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr long kMaxCells = 1L << 26;

}  // namespace

VirtualScanner::VirtualScanner(std::vector<geometry::Segment2> segments,
                               const VirtualScannerOptions& options)
    : segments_(std::move(segments)), cell_size_m_(options.cell_size_m) {
  if (!(options.cell_size_m > 0.0)) {
    throw std::invalid_argument("virtual_scanner.cell_size_m must be > 0 m, got " +
                                std::to_string(options.cell_size_m));
  }
  edges_.reserve(segments_.size());
  for (const geometry::Segment2& s : segments_) {
    edges_.push_back({s.start_m.x(), s.start_m.y(), s.end_m.x() - s.start_m.x(),
                      s.end_m.y() - s.start_m.y()});
  }
  BuildIndex();
}

void VirtualScanner::BuildIndex() {
  if (segments_.empty()) return;
  min_m_ = max_m_ = segments_.front().start_m;
  for (const geometry::Segment2& s : segments_) {
    min_m_ = min_m_.cwiseMin(s.start_m).cwiseMin(s.end_m);
    max_m_ = max_m_.cwiseMax(s.start_m).cwiseMax(s.end_m);
  }
  const Eigen::Vector2d extent = max_m_ - min_m_;
  const double cells_x = std::floor(extent.x() / cell_size_m_) + 1.0;
  const double cells_y = std::floor(extent.y() / cell_size_m_) + 1.0;
  if (cells_x * cells_y > static_cast<double>(kMaxCells)) {
    throw std::invalid_argument("virtual_scanner.cell_size_m (" + std::to_string(cell_size_m_) +
                                " m) is too small for a plan of " + std::to_string(extent.x()) +
                                " x " + std::to_string(extent.y()) + " m");
  }
  width_ = static_cast<int>(cells_x);
  height_ = static_cast<int>(cells_y);
  // A segment goes into every cell it may cross: the cells of its bounding box whose centre is
  // within half a cell diagonal of it (conservative, so the walk never misses a wall).
  const double reach = 0.5 * std::sqrt(2.0) * cell_size_m_ * (1.0 + 1e-9);
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(width_ * height_));
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const geometry::Segment2& s = segments_[i];
    const Eigen::Vector2d lo = s.start_m.cwiseMin(s.end_m) - min_m_;
    const Eigen::Vector2d hi = s.start_m.cwiseMax(s.end_m) - min_m_;
    const int x0 = std::max(0, static_cast<int>(std::floor(lo.x() / cell_size_m_)));
    const int y0 = std::max(0, static_cast<int>(std::floor(lo.y() / cell_size_m_)));
    const int x1 = std::min(width_ - 1, static_cast<int>(std::floor(hi.x() / cell_size_m_)));
    const int y1 = std::min(height_ - 1, static_cast<int>(std::floor(hi.y() / cell_size_m_)));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d centre = min_m_ + cell_size_m_ * Eigen::Vector2d(x + 0.5, y + 0.5);
        if (geometry::DistanceToSegment(s, centre) > reach) continue;
        cells[static_cast<std::size_t>(y * width_ + x)].push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    cell_start_[c + 1] = cell_start_[c] + static_cast<std::uint32_t>(cells[c].size());
    cell_items_.insert(cell_items_.end(), cells[c].begin(), cells[c].end());
  }
}

double VirtualScanner::NearestInCell(std::size_t cell, double ox, double oy, double dx, double dy,
                                     double best) const {
  // origin + r d = start + u edge by Cramer's rule, as geometry::RaySegmentIntersection, inlined
  // because this is the inner loop of every virtual scan.
  for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const Edge& e = edges_[cell_items_[k]];
    const double denom = dx * e.ey - dy * e.ex;
    if (std::abs(denom) < 1e-12) continue;  // parallel: a grazing ray sees no wall
    const double tx = e.sx - ox;
    const double ty = e.sy - oy;
    const double range = (tx * e.ey - ty * e.ex) / denom;
    if (range <= 0.0 || range >= best) continue;
    const double u = (tx * dy - ty * dx) / denom;
    if (u < 0.0 || u > 1.0) continue;
    best = range;
  }
  return best;
}

double VirtualScanner::CastRay(const Eigen::Vector2d& origin_m,
                               const Eigen::Vector2d& direction_unit, double max_range_m) const {
  if (width_ == 0) return kInfinity;
  const double ox = origin_m.x(), oy = origin_m.y();
  const double dx = direction_unit.x(), dy = direction_unit.y();
  const double gx = min_m_.x(), gy = min_m_.y();
  const double size_x = width_ * cell_size_m_, size_y = height_ * cell_size_m_;
  // Clip the ray to the grid box (slab method): [t_in, t_out].
  double t_in = 0.0, t_out = max_range_m;
  const auto clip = [&](double o, double d, double low, double high) {
    if (d == 0.0) return o >= low && o <= high;
    double a = (low - o) / d, b = (high - o) / d;
    if (a > b) std::swap(a, b);
    t_in = std::max(t_in, a);
    t_out = std::min(t_out, b);
    return t_in <= t_out;
  };
  if (!clip(ox, dx, gx, gx + size_x) || !clip(oy, dy, gy, gy + size_y)) return kInfinity;
  int ix = std::clamp(static_cast<int>(std::floor((ox + t_in * dx - gx) / cell_size_m_)), 0,
                      width_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((oy + t_in * dy - gy) / cell_size_m_)), 0,
                      height_ - 1);
  const int step_x = dx > 0.0 ? 1 : -1, step_y = dy > 0.0 ? 1 : -1;
  double t_max_x = dx != 0.0 ? (gx + (ix + (dx > 0.0 ? 1 : 0)) * cell_size_m_ - ox) / dx : kInfinity;
  double t_max_y = dy != 0.0 ? (gy + (iy + (dy > 0.0 ? 1 : 0)) * cell_size_m_ - oy) / dy : kInfinity;
  const double t_delta_x = dx != 0.0 ? cell_size_m_ / std::abs(dx) : kInfinity;
  const double t_delta_y = dy != 0.0 ? cell_size_m_ / std::abs(dy) : kInfinity;
  double best = kInfinity;
  for (;;) {
    best = NearestInCell(static_cast<std::size_t>(iy * width_ + ix), ox, oy, dx, dy, best);
    const double t_exit = std::min(t_max_x, t_max_y);
    // Cells come in ray order, so a hit before this cell's exit cannot be beaten further on.
    if (best <= t_exit || t_exit > t_out) break;
    if (t_max_x < t_max_y) {
      ix += step_x;
      t_max_x += t_delta_x;
      if (ix < 0 || ix >= width_) break;
    } else {
      iy += step_y;
      t_max_y += t_delta_y;
      if (iy < 0 || iy >= height_) break;
    }
  }
  return best < max_range_m ? best : kInfinity;
}

void VirtualScanner::CastScan(const geometry::Pose2& map_from_laser,
                              const sensors::LaserGeometry& geometry, std::size_t beams,
                              std::vector<float>& ranges_m) const {
  ranges_m.resize(beams);
  const Eigen::Vector2d origin(map_from_laser.x_m, map_from_laser.y_m);
  const double first = map_from_laser.theta_rad + geometry.angle_min_rad;
  // Beam directions by rotating the first one step by step: two sines per scan, not per beam.
  Eigen::Vector2d direction(std::cos(first), std::sin(first));
  const double c = std::cos(geometry.angle_increment_rad);
  const double s = std::sin(geometry.angle_increment_rad);
  for (std::size_t i = 0; i < beams; ++i) {
    const double range = CastRay(origin, direction, geometry.max_range_m);
    ranges_m[i] = std::isfinite(range) ? static_cast<float>(range) : sensors::LaserScan::kNoReturn;
    direction = Eigen::Vector2d(c * direction.x() - s * direction.y(),
                                s * direction.x() + c * direction.y());
  }
}

sensors::LaserScan VirtualScanner::Scan(const geometry::Pose2& map_from_laser,
                                        const sensors::LaserGeometry& geometry, std::size_t beams,
                                        double stamp_s) const {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = geometry;
  CastScan(map_from_laser, geometry, beams, scan.ranges_m);
  return scan;
}

}  // namespace pena::localisation
