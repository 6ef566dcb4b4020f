#include "loop_walls.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace pena::line_map::testing {
namespace {

using Eigen::Vector2d;

constexpr double kStopSpacingM = 4.0;
constexpr double kSightRadiusM = 5.0;

// The part of `wall` within `radius_m` of `centre`, if longer than 0.3 m.
std::optional<geometry::Segment2> ClipToDisk(const geometry::Segment2& wall, const Vector2d& centre,
                                             double radius_m) {
  const Vector2d d = wall.end_m - wall.start_m;
  const Vector2d f = wall.start_m - centre;
  const double a = d.squaredNorm();
  const double b = 2.0 * f.dot(d);
  const double c = f.squaredNorm() - radius_m * radius_m;
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant <= 0.0) return std::nullopt;
  const double t0 = std::max(0.0, (-b - std::sqrt(discriminant)) / (2.0 * a));
  const double t1 = std::min(1.0, (-b + std::sqrt(discriminant)) / (2.0 * a));
  if ((t1 - t0) * std::sqrt(a) < 0.3) return std::nullopt;
  return geometry::Segment2{wall.start_m + t0 * d, wall.start_m + t1 * d};
}

// The corridor's centre line: a 18 m x 10 m rectangle, at `s_m` metres along it.
Vector2d AlongLoop(double s_m) {
  const std::vector<Vector2d> corners = {{1, 1}, {19, 1}, {19, 11}, {1, 11}, {1, 1}};
  double left = std::fmod(s_m, 56.0);
  for (std::size_t i = 0; i + 1 < corners.size(); ++i) {
    const double leg = (corners[i + 1] - corners[i]).norm();
    if (left <= leg) return corners[i] + left / leg * (corners[i + 1] - corners[i]);
    left -= leg;
  }
  return corners.front();
}

}  // namespace

std::vector<geometry::Segment2> LoopWalls() {
  const auto wall = [](double x0, double y0, double x1, double y1) {
    return geometry::Segment2{Vector2d(x0, y0), Vector2d(x1, y1)};
  };
  return {// Outer walls, the south one with a 1 m doorway at x = 8..9.
          wall(0, 0, 8, 0), wall(9, 0, 20, 0), wall(20, 0, 20, 12), wall(20, 12, 0, 12),
          wall(0, 12, 0, 0),
          // Inner block, the north side with a 1 m doorway at x = 10..11.
          wall(2, 2, 18, 2), wall(18, 2, 18, 10), wall(18, 10, 11, 10), wall(10, 10, 2, 10),
          wall(2, 10, 2, 2)};
}

LineSegment Piece(double x0, double y0, double x1, double y1, double observations) {
  LineSegment piece;
  piece.segment = {Vector2d(x0, y0), Vector2d(x1, y1)};
  piece.observations = observations;
  piece.support_cells = std::round(geometry::Length(piece.segment) / 0.05);
  piece.rms_error_m = 0.01;
  return piece;
}

std::vector<std::vector<LineSegment>> WalkLoop(int passes, double jitter_m, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> jitter(0.0, jitter_m);
  std::vector<std::vector<LineSegment>> batches;
  const int stops = static_cast<int>(56.0 / kStopSpacingM) * passes;
  for (int stop = 0; stop < stops; ++stop) {
    const Vector2d position = AlongLoop(kStopSpacingM * stop);
    std::vector<LineSegment> batch;
    for (const geometry::Segment2& wall : LoopWalls()) {
      const auto seen = ClipToDisk(wall, position, kSightRadiusM);
      if (!seen) continue;
      const Vector2d along = (seen->end_m - seen->start_m).normalized();
      const Vector2d normal(-along.y(), along.x());
      const Vector2d start = seen->start_m + jitter(random) * normal + jitter(random) * along;
      const Vector2d end = seen->end_m + jitter(random) * normal + jitter(random) * along;
      batch.push_back(Piece(start.x(), start.y(), end.x(), end.y(),
                            std::round(20.0 * geometry::Length(*seen))));
    }
    batches.push_back(std::move(batch));
  }
  return batches;
}

double TotalLength(const std::vector<LineSegment>& segments) {
  double total_m = 0.0;
  for (const LineSegment& segment : segments) total_m += geometry::Length(segment.segment);
  return total_m;
}

}  // namespace pena::line_map::testing
