#include "plan_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pena::fusion::detail {
namespace {

// Smallest angle between two directions taken modulo pi.
double LineAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double angle = std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
  return std::min(angle, std::numbers::pi - angle);
}

}  // namespace

std::vector<line_map::LineSegment> OverlayPlanWall(const line_map::LineSegment& plan_wall,
                                                   const std::string& plan_key,
                                                   std::vector<line_map::LineSegment>& observed,
                                                   const GlobalMapOptions& options) {
  const Eigen::Vector2d start = plan_wall.segment.start_m;
  const Eigen::Vector2d along = plan_wall.segment.end_m - start;
  const double length = along.norm();
  if (length <= 0.0) return {};
  const Eigen::Vector2d unit = along / length;
  const Eigen::Vector2d normal(-unit.y(), unit.x());
  std::vector<std::pair<double, double>> covered;
  for (line_map::LineSegment& wall : observed) {
    const Eigen::Vector2d a = wall.segment.start_m - start;
    const Eigen::Vector2d b = wall.segment.end_m - start;
    const double offset_m = std::max(std::abs(a.dot(normal)), std::abs(b.dot(normal)));
    if (LineAngle(along, b - a) > options.merge.merge_angle_rad || offset_m > options.plan_shadow_m) {
      continue;
    }
    const double from = std::clamp(std::min(a.dot(unit), b.dot(unit)), 0.0, length);
    const double to = std::clamp(std::max(a.dot(unit), b.dot(unit)), 0.0, length);
    if (to <= from) continue;
    covered.emplace_back(from, to);
    if (offset_m <= options.merge.merge_distance_m &&
        std::find(wall.provenance.begin(), wall.provenance.end(), plan_key) == wall.provenance.end()) {
      wall.provenance.push_back(plan_key);
      std::sort(wall.provenance.begin(), wall.provenance.end());
    }
  }
  std::sort(covered.begin(), covered.end());
  std::vector<line_map::LineSegment> pieces;
  double free_from = 0.0;
  const auto add_piece = [&](double from, double to) {
    if (to - from < options.min_plan_piece_m) return;
    line_map::LineSegment piece;
    piece.segment.start_m = start + from * unit;
    piece.segment.end_m = start + to * unit;
    piece.provenance = {plan_key};
    pieces.push_back(line_map::QuantiseSegment(piece));
  };
  for (const auto& [from, to] : covered) {
    add_piece(free_from, from);
    free_from = std::max(free_from, to);
  }
  add_piece(free_from, length);
  return pieces;
}

}  // namespace pena::fusion::detail
