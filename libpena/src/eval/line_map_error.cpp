#include "pena/eval/line_map_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pena::eval {

namespace {

// Points along a segment, each standing for an equal share of its length.
struct Samples {
  std::vector<Eigen::Vector2d> points_m;
  double weight_m = 0.0;
};

Samples Sample(const geometry::Segment2& segment, double step_m) {
  const double length_m = geometry::Length(segment);
  const auto count =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(length_m / step_m)));
  Samples samples;
  samples.weight_m = length_m / static_cast<double>(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double t = (static_cast<double>(k) + 0.5) / static_cast<double>(count);
    samples.points_m.push_back(segment.start_m + t * (segment.end_m - segment.start_m));
  }
  return samples;
}

// |cos| of the angle between two segments' lines (1 when either has no direction).
double AbsCos(const geometry::Segment2& a, const geometry::Segment2& b) {
  const Eigen::Vector2d da = a.end_m - a.start_m;
  const Eigen::Vector2d db = b.end_m - b.start_m;
  const double norms = da.norm() * db.norm();
  return norms > 0.0 ? std::abs(da.dot(db)) / norms : 1.0;
}

// Cheap rejection: can any point of `a` be within `distance_m` of `b`? (Bounding boxes.)
bool Near(const geometry::Segment2& a, const geometry::Segment2& b, double distance_m) {
  const Eigen::Vector2d a_min = a.start_m.cwiseMin(a.end_m).array() - distance_m;
  const Eigen::Vector2d a_max = a.start_m.cwiseMax(a.end_m).array() + distance_m;
  const Eigen::Vector2d b_min = b.start_m.cwiseMin(b.end_m);
  const Eigen::Vector2d b_max = b.start_m.cwiseMax(b.end_m);
  return (a_min.array() <= b_max.array()).all() && (b_min.array() <= a_max.array()).all();
}

void Validate(const LineMapErrorOptions& o) {
  auto require = [](bool ok, const char* field, const char* rule, double value) {
    if (!ok) {
      throw std::invalid_argument(std::string("line_map_error.") + field + " must be " + rule +
                                  ", got " + std::to_string(value));
    }
  };
  require(o.distance_m > 0.0, "distance_m", "> 0 m", o.distance_m);
  require(o.angle_rad >= 0.0 && o.angle_rad <= std::numbers::pi / 2, "angle_rad",
          "in [0, pi/2] rad", o.angle_rad);
  require(o.sample_step_m > 0.0, "sample_step_m", "> 0 m", o.sample_step_m);
  require(o.min_fragment_m >= 0.0, "min_fragment_m", ">= 0 m", o.min_fragment_m);
}

// Coverage of one wall, and how many map segments are fragments of it.
void ScoreWall(const geometry::Segment2& wall, const std::vector<geometry::Segment2>& map,
               const LineMapErrorOptions& options, LineMapErrorSummary& summary) {
  const double min_cos = std::cos(options.angle_rad);
  std::vector<std::size_t> candidates;
  for (std::size_t m = 0; m < map.size(); ++m) {
    if (AbsCos(wall, map[m]) >= min_cos && Near(wall, map[m], options.distance_m)) {
      candidates.push_back(m);
    }
  }
  const Samples samples = Sample(wall, options.sample_step_m);
  std::vector<double> covered_by_m(candidates.size(), 0.0);
  for (const Eigen::Vector2d& point : samples.points_m) {
    bool covered = false;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (geometry::DistanceToSegment(map[candidates[c]], point) <= options.distance_m) {
        covered_by_m[c] += samples.weight_m;
        covered = true;
      }
    }
    if (covered) summary.covered_length_m += samples.weight_m;
  }
  const double wall_length_m = geometry::Length(wall);
  summary.wall_length_m += wall_length_m;
  const double fragment_m = std::min(options.min_fragment_m, 0.5 * wall_length_m);
  const auto fragments =
      std::count_if(covered_by_m.begin(), covered_by_m.end(),
                    [&](double length_m) { return length_m >= fragment_m && length_m > 0.0; });
  if (fragments > 0) {
    summary.fragmentation += static_cast<double>(fragments);
    ++summary.walls_matched;
  }
}

// Map length within the distance of any wall (no direction test: any wall there is real).
void ScoreMapSegment(const geometry::Segment2& segment,
                     const std::vector<geometry::Segment2>& walls,
                     const LineMapErrorOptions& options, LineMapErrorSummary& summary) {
  std::vector<std::size_t> candidates;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (Near(segment, walls[w], options.distance_m)) candidates.push_back(w);
  }
  const Samples samples = Sample(segment, options.sample_step_m);
  for (const Eigen::Vector2d& point : samples.points_m) {
    const bool precise = std::any_of(candidates.begin(), candidates.end(), [&](std::size_t w) {
      return geometry::DistanceToSegment(walls[w], point) <= options.distance_m;
    });
    if (precise) summary.precise_length_m += samples.weight_m;
  }
  summary.map_length_m += geometry::Length(segment);
}

}  // namespace

LineMapErrorSummary EvaluateLineMap(const std::vector<geometry::Segment2>& map,
                                    const std::vector<geometry::Segment2>& walls,
                                    const LineMapErrorOptions& options) {
  Validate(options);
  LineMapErrorSummary summary;
  summary.map_segments = map.size();
  summary.walls = walls.size();
  for (const geometry::Segment2& wall : walls) ScoreWall(wall, map, options, summary);
  for (const geometry::Segment2& segment : map) ScoreMapSegment(segment, walls, options, summary);
  if (summary.wall_length_m > 0.0)
    summary.coverage = summary.covered_length_m / summary.wall_length_m;
  if (summary.map_length_m > 0.0)
    summary.precision = summary.precise_length_m / summary.map_length_m;
  if (summary.walls_matched > 0) {
    summary.fragmentation /= static_cast<double>(summary.walls_matched);
  }
  return summary;
}

}  // namespace pena::eval
