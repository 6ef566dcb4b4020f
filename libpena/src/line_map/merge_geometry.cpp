#include "merge_geometry.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pena::line_map::detail {
namespace {

// Mean squared distance to a line of a segment whose endpoints lie e0 and e1 from it (signed):
// the integral of (e0 + s (e1 - e0))^2 over s in [0, 1].
double MeanSquaredOffset(double e0, double e1) { return (e0 * e0 + e0 * e1 + e1 * e1) / 3.0; }

}  // namespace

bool SameWall(const geometry::Segment2& a, const geometry::Segment2& b,
              const LineMapOptions& options) {
  const bool a_longer = geometry::Length(a) >= geometry::Length(b);
  const geometry::Segment2& longer = a_longer ? a : b;
  const geometry::Segment2& shorter = a_longer ? b : a;
  const double long_m = geometry::Length(longer);
  const double short_m = geometry::Length(shorter);
  if (long_m <= 0.0) return false;
  const Eigen::Vector2d u = (longer.end_m - longer.start_m) / long_m;
  if (short_m > 0.0) {
    const Eigen::Vector2d v = (shorter.end_m - shorter.start_m) / short_m;
    if (std::abs(u.dot(v)) < std::cos(options.merge_angle_rad)) return false;
  }
  const Eigen::Vector2d normal(-u.y(), u.x());
  const Eigen::Vector2d s0 = shorter.start_m - longer.start_m;
  const Eigen::Vector2d s1 = shorter.end_m - longer.start_m;
  if (std::max(std::abs(normal.dot(s0)), std::abs(normal.dot(s1))) > options.merge_distance_m) {
    return false;
  }
  // Positions along the longer segment, which spans [0, long_m]; a negative gap is an overlap.
  const double low = std::min(u.dot(s0), u.dot(s1));
  const double high = std::max(u.dot(s0), u.dot(s1));
  return std::max(low - long_m, -high) <= options.max_gap_m;
}

double Weight(const LineSegment& part) {
  if (part.observations > 0.0) return part.observations;
  if (part.support_cells > 0.0) return part.support_cells;
  return std::max(geometry::Length(part.segment), kCoordinateQuantumM);
}

LineSegment OrientLike(LineSegment line, const geometry::Segment2& reference) {
  if ((line.segment.end_m - line.segment.start_m).dot(reference.end_m - reference.start_m) < 0.0) {
    std::swap(line.segment.start_m, line.segment.end_m);
  }
  return line;
}

bool WithinBand(const geometry::Segment2& piece, const geometry::Segment2& line, double band_m) {
  const double length_m = geometry::Length(line);
  if (length_m <= 0.0) return false;
  const Eigen::Vector2d u = (line.end_m - line.start_m) / length_m;
  const Eigen::Vector2d normal(-u.y(), u.x());
  return std::abs(normal.dot(piece.start_m - line.start_m)) <= band_m &&
         std::abs(normal.dot(piece.end_m - line.start_m)) <= band_m;
}

LineSegment Refit(const std::vector<const LineSegment*>& parts,
                  const std::vector<const LineSegment*>& span_only) {
  // Each part is a uniform mass along its segment: its scatter about the common centroid is the
  // offset of its midpoint plus d d^T / 12 (the second moment of a uniform segment of vector d).
  double total_weight = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const LineSegment* part : parts) {
    const double w = Weight(*part);
    total_weight += w;
    centroid += w * 0.5 * (part->segment.start_m + part->segment.end_m);
  }
  centroid /= total_weight;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const LineSegment* part : parts) {
    const Eigen::Vector2d mid = 0.5 * (part->segment.start_m + part->segment.end_m) - centroid;
    const Eigen::Vector2d d = part->segment.end_m - part->segment.start_m;
    scatter += Weight(*part) * (mid * mid.transpose() + d * d.transpose() / 12.0);
  }
  // Principal axis of a symmetric 2x2 matrix in closed form.
  const double theta =
      0.5 * std::atan2(2.0 * scatter(0, 1), scatter(0, 0) - scatter(1, 1));
  Eigen::Vector2d u(std::cos(theta), std::sin(theta));
  if (u.dot(parts.front()->segment.end_m - parts.front()->segment.start_m) < 0.0) u = -u;
  const Eigen::Vector2d normal(-u.y(), u.x());

  LineSegment merged;
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  double weighted_square_m2 = 0.0;
  std::vector<const LineSegment*> all = parts;
  all.insert(all.end(), span_only.begin(), span_only.end());
  for (const LineSegment* part : span_only) total_weight += Weight(*part);
  for (const LineSegment* part : all) {
    const double e0 = normal.dot(part->segment.start_m - centroid);
    const double e1 = normal.dot(part->segment.end_m - centroid);
    weighted_square_m2 += Weight(*part) * (part->rms_error_m * part->rms_error_m +
                                           MeanSquaredOffset(e0, e1));
    for (const Eigen::Vector2d& p : {part->segment.start_m, part->segment.end_m}) {
      low = std::min(low, u.dot(p - centroid));
      high = std::max(high, u.dot(p - centroid));
    }
  }
  for (const LineSegment* part : parts) {
    merged.support_cells += part->support_cells;
    merged.observations += part->observations;
  }
  merged.segment.start_m = centroid + low * u;
  merged.segment.end_m = centroid + high * u;
  merged.rms_error_m = std::sqrt(weighted_square_m2 / total_weight);
  return merged;
}

}  // namespace pena::line_map::detail
