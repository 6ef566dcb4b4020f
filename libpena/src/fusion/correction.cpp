#include "pena/fusion/correction.hpp"

#include <algorithm>
#include <cmath>

#include "fusion_checks.hpp"
#include "pena/localisation/virtual_scanner.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::fusion {
namespace {

void Validate(const CorrectionOptions& options) {
  using detail::Require;
  Require(options.min_score > 0.0 && options.min_score <= 1.0,
          "correction.min_score must be in (0, 1]", options.min_score);
  Require(options.min_hits >= 1, "correction.min_hits must be >= 1 (points)", options.min_hits);
  Require(options.oversample >= 1, "correction.oversample must be >= 1 (beams per beam)",
          options.oversample);
  Require(std::isfinite(options.min_range_m) && options.min_range_m >= 0.0,
          "correction.min_range_m must be >= 0 (metres)", options.min_range_m);
  Require(std::isfinite(options.max_range_m) && options.max_range_m > options.min_range_m,
          "correction.max_range_m must be > min_range_m (metres)", options.max_range_m);
  scan_matching::ValidateWindow(options.window, options.matcher);
}

// The real scan's returns in the body frame within the ranges used.
scan_matching::Points2 RealPoints(const sensors::LaserScan& scan, const CorrectionOptions& options) {
  scan_matching::Points2 points;
  for (const Eigen::Vector2d& p : scan_matching::ScanToPoints(scan, options.min_range_m)) {
    if (p.norm() <= options.max_range_m) points.push_back(p);
  }
  return points;
}

// The virtual scan (section 4.2) of `map` from map_from_body, as points in the body frame; denser
// than the real scan so that every real point has a close reference point.
scan_matching::Points2 VirtualPoints(const sensors::LaserScan& scan,
                                     const geometry::Pose2& map_from_body,
                                     const std::vector<geometry::Segment2>& map,
                                     const CorrectionOptions& options) {
  sensors::LaserGeometry geometry = scan.geometry;
  geometry.angle_increment_rad /= options.oversample;
  geometry.max_range_m = std::min(geometry.max_range_m, options.max_range_m + 2.0);
  const std::size_t beams = scan.ranges_m.size() * static_cast<std::size_t>(options.oversample);
  const localisation::VirtualScanner scanner(map);
  const sensors::LaserScan virtual_scan = scanner.Scan(map_from_body, geometry, beams);
  return scan_matching::ScanToPoints(virtual_scan, options.min_range_m);
}

}  // namespace

FusionCorrection ComputeCorrection(const std::string& entity_id, const sensors::LaserScan& scan,
                                   const geometry::Pose2& entity_from_body,
                                   const geometry::Pose2& map_from_entity,
                                   const std::vector<geometry::Segment2>& map,
                                   const CorrectionOptions& options) {
  Validate(options);
  FusionCorrection correction;
  correction.entity_id = entity_id;
  correction.map_from_entity = map_from_entity;
  const geometry::Pose2 map_from_body = geometry::Compose(map_from_entity, entity_from_body);
  correction.predicted_map_from_body = map_from_body;
  correction.matched_map_from_body = map_from_body;
  const scan_matching::Points2 real = RealPoints(scan, options);
  const scan_matching::Points2 reference = VirtualPoints(scan, map_from_body, map, options);
  correction.points = static_cast<int>(real.size());
  if (real.size() < static_cast<std::size_t>(options.min_hits) ||
      reference.size() < static_cast<std::size_t>(options.min_hits)) {
    correction.reason = "too few points: " + std::to_string(real.size()) + " real, " +
                        std::to_string(reference.size()) + " virtual";
    return correction;
  }
  // The reference is the virtual scan in the predicted body frame, so the match is
  // predicted_from_actual: the body's true pose seen from where the alignment put it.
  const scan_matching::CorrelationScanMatcher matcher(options.matcher, reference);
  const scan_matching::MatchResult match =
      matcher.MatchBranchAndBound(real, geometry::Pose2{}, options.window);
  correction.score = match.score;
  correction.hits = match.hits;
  correction.information = match.information;
  if (!match.converged || match.score < options.min_score || match.hits < options.min_hits) {
    correction.reason = "weak match: score " + std::to_string(match.score) + ", " +
                        std::to_string(match.hits) + " hits";
    return correction;
  }
  const geometry::Pose2 corrected_map_from_body =
      geometry::Compose(map_from_body, match.reference_from_scan);
  correction.matched_map_from_body = corrected_map_from_body;
  correction.map_from_entity =
      geometry::Compose(corrected_map_from_body, geometry::Inverse(entity_from_body));
  correction.accepted = true;
  const double support = std::min(1.0, static_cast<double>(match.hits) / (2.0 * options.min_hits));
  correction.confidence = std::clamp(match.score * support, 0.0, 1.0);
  return correction;
}

}  // namespace pena::fusion
