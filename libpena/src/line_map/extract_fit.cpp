// Straight pieces of skeleton chains: recursive splitting and total-least-squares fits (paper
// section 3: "recursive boundary splitting and a least-squares line fit").
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "extract_steps.hpp"

namespace pena::line_map::internal {

namespace {

std::vector<Eigen::Vector2d> ToWorld(const std::vector<cv::Point>& pixels, const GridFrame& frame) {
  std::vector<Eigen::Vector2d> points_m;
  points_m.reserve(pixels.size());
  for (const cv::Point& pixel : pixels) points_m.push_back(frame.ToWorld(pixel));
  return points_m;
}

// Index in [first, last] of the point farthest from the chord first-last (or from the first
// point when the chain is closed), with that distance.
std::pair<std::size_t, double> Farthest(const std::vector<Eigen::Vector2d>& points_m,
                                        std::size_t first, std::size_t last) {
  const geometry::Segment2 chord{points_m[first], points_m[last]};
  std::pair<std::size_t, double> best{first, 0.0};
  for (std::size_t k = first + 1; k < last; ++k) {
    const double distance_m = geometry::DistanceToSegment(chord, points_m[k]);
    if (distance_m > best.second) best = {k, distance_m};
  }
  return best;
}

Eigen::Vector2d Direction(const geometry::Segment2& segment) {
  const Eigen::Vector2d along = segment.end_m - segment.start_m;
  const double length_m = along.norm();
  return length_m > 0.0 ? Eigen::Vector2d(along / length_m) : Eigen::Vector2d::UnitX();
}

// Shortest distance between two segments that do not cross (pieces of one skeleton never do).
double Gap(const geometry::Segment2& a, const geometry::Segment2& b) {
  return std::min(
      {geometry::DistanceToSegment(a, b.start_m), geometry::DistanceToSegment(a, b.end_m),
       geometry::DistanceToSegment(b, a.start_m), geometry::DistanceToSegment(b, a.end_m)});
}

// Do both segments lie along `line`? Judged at their fitted ends, which one bump of the skeleton
// (speckle bridged onto a wall) hardly moves, unlike the largest pixel deviation.
bool EndsNearLine(const geometry::Segment2& a, const geometry::Segment2& b,
                  const geometry::Segment2& line, double tolerance_m) {
  const Eigen::Vector2d direction = Direction(line);
  for (const Eigen::Vector2d& p : {a.start_m, a.end_m, b.start_m, b.end_m}) {
    const Eigen::Vector2d offset = p - line.start_m;
    if (std::abs(direction.x() * offset.y() - direction.y() * offset.x()) > tolerance_m) {
      return false;
    }
  }
  return true;
}

}  // namespace

LineFit FitLine(const std::vector<Eigen::Vector2d>& points_m) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points_m) centroid += p;
  centroid /= static_cast<double>(points_m.size());
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Eigen::Vector2d& p : points_m) {
    const Eigen::Vector2d d = p - centroid;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  // Principal axis of the 2x2 scatter matrix in closed form: minimises perpendicular distances.
  const double angle_rad = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const Eigen::Vector2d direction(std::cos(angle_rad), std::sin(angle_rad));
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  double t_min = std::numeric_limits<double>::infinity();
  double t_max = -t_min;
  LineFit fit;
  for (const Eigen::Vector2d& p : points_m) {
    const double t = direction.dot(p - centroid);
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
    fit.max_deviation_m = std::max(fit.max_deviation_m, std::abs(normal.dot(p - centroid)));
  }
  fit.segment = {centroid + t_min * direction, centroid + t_max * direction};
  return fit;
}

std::vector<Piece> SplitChain(const PixelChain& chain, const GridFrame& frame,
                              double split_distance_m) {
  const std::vector<Eigen::Vector2d> points_m = ToWorld(chain, frame);
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, chain.size() - 1}};
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  while (!todo.empty()) {
    const auto [first, last] = todo.back();
    todo.pop_back();
    const auto [split, distance_m] = Farthest(points_m, first, last);
    if (distance_m > split_distance_m) {
      todo.emplace_back(split, last);  // the stack pops the first half first: chain order kept
      todo.emplace_back(first, split);
    } else {
      ranges.emplace_back(first, last);
    }
  }
  std::vector<Piece> pieces;
  for (const auto& [first, last] : ranges) {
    Piece piece;
    piece.pixels.assign(chain.begin() + static_cast<std::ptrdiff_t>(first),
                        chain.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    piece.fit = FitLine({points_m.begin() + static_cast<std::ptrdiff_t>(first),
                         points_m.begin() + static_cast<std::ptrdiff_t>(last) + 1});
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

std::vector<Piece> MergeCollinear(std::vector<Piece> pieces, const GridFrame& frame, double gap_m,
                                  double angle_rad, double split_distance_m) {
  const double min_cos = std::cos(angle_rad);
  std::vector<bool> gone(pieces.size(), false);
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      for (std::size_t j = i + 1; j < pieces.size() && !gone[i]; ++j) {
        if (gone[j]) continue;
        const geometry::Segment2& a = pieces[i].fit.segment;
        const geometry::Segment2& b = pieces[j].fit.segment;
        if (Gap(a, b) > gap_m) continue;
        // The direction of a piece shorter than twice the split distance says little: only the
        // joint fit below decides for it.
        const double shorter_m = std::min(geometry::Length(a), geometry::Length(b));
        if (shorter_m >= 2.0 * split_distance_m &&
            std::abs(Direction(a).dot(Direction(b))) < min_cos) {
          continue;
        }
        std::vector<cv::Point> pixels = pieces[i].pixels;
        pixels.insert(pixels.end(), pieces[j].pixels.begin(), pieces[j].pixels.end());
        const LineFit fit = FitLine(ToWorld(pixels, frame));
        if (!EndsNearLine(a, b, fit.segment, 0.5 * split_distance_m)) continue;
        pieces[i] = {std::move(pixels), fit};
        gone[j] = true;
        changed = true;
      }
    }
  }
  std::vector<Piece> kept;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (!gone[i]) kept.push_back(std::move(pieces[i]));
  }
  return kept;
}

}  // namespace pena::line_map::internal
