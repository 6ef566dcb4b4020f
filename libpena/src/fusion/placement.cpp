#include "pena/fusion/placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "fusion_checks.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "placement_geometry.hpp"

namespace pena::fusion {
namespace {

using detail::DistanceField;
using detail::Samples;

constexpr std::size_t kCoarseKept = 64;  // hypotheses refined after the coarse scoring
constexpr std::size_t kCoarseStride = 5; // every 5th sample point in the coarse scoring

// Best first, ties broken by pose so the order does not depend on the input order.
bool Better(const PlacementHypothesis& a, const PlacementHypothesis& b) {
  if (a.score != b.score) return a.score > b.score;
  const geometry::Pose2& p = a.map_from_entity;
  const geometry::Pose2& q = b.map_from_entity;
  return std::tie(p.x_m, p.y_m, p.theta_rad) < std::tie(q.x_m, q.y_m, q.theta_rad);
}

bool Same(const geometry::Pose2& a, const geometry::Pose2& b, const PlacementOptions& options) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) < options.distinct_distance_m &&
         std::abs(geometry::NormalizeAngle(a.theta_rad - b.theta_rad)) < options.distinct_angle_rad;
}

// Coordinate descent on the fine score with shrinking steps: corner poses are off by the line
// fits' errors (centimetres, a degree).
PlacementHypothesis Refine(geometry::Pose2 pose, const Samples& samples, const DistanceField& field,
                           double score_distance_m) {
  double best = field.Score(samples, pose, score_distance_m, 1);
  const double deg = std::numbers::pi / 180.0;
  for (const auto& [step_m, step_rad] : {std::pair{0.10, 1.0 * deg}, std::pair{0.05, 0.5 * deg},
                                         std::pair{0.02, 0.2 * deg}}) {
    for (int round = 0; round < 10; ++round) {
      geometry::Pose2 next = pose;
      for (const geometry::Pose2& move :
           {geometry::Pose2{step_m, 0, 0}, geometry::Pose2{-step_m, 0, 0},
            geometry::Pose2{0, step_m, 0}, geometry::Pose2{0, -step_m, 0},
            geometry::Pose2{0, 0, step_rad}, geometry::Pose2{0, 0, -step_rad}}) {
        const geometry::Pose2 candidate{pose.x_m + move.x_m, pose.y_m + move.y_m,
                                        geometry::NormalizeAngle(pose.theta_rad + move.theta_rad)};
        const double score = field.Score(samples, candidate, score_distance_m, 1);
        if (score > best) {
          best = score;
          next = candidate;
        }
      }
      if (next.x_m == pose.x_m && next.y_m == pose.y_m && next.theta_rad == pose.theta_rad) break;
      pose = next;
    }
  }
  return {pose, best, best * samples.length_m};
}

// Candidate poses from every pair of corners with the same opening angle.
std::vector<geometry::Pose2> CornerPoses(const std::vector<line_map::LineSegment>& local,
                                         const std::vector<line_map::LineSegment>& global,
                                         const PlacementOptions& options) {
  const auto local_corners = detail::FindCorners(local, options.max_local_segments, options);
  const auto global_corners = detail::FindCorners(global, options.max_global_segments, options);
  std::vector<geometry::Pose2> poses;
  for (const detail::Corner& l : local_corners) {
    for (const detail::Corner& g : global_corners) {
      if (std::abs(l.opening_rad - g.opening_rad) > options.corner_angle_tolerance_rad) continue;
      const double theta1 = geometry::NormalizeAngle(g.first_rad - l.first_rad);
      const double theta2 = geometry::NormalizeAngle(g.second_rad - l.second_rad);
      const double theta =
          geometry::NormalizeAngle(theta1 + geometry::NormalizeAngle(theta2 - theta1) / 2.0);
      const Eigen::Vector2d rotated =
          geometry::TransformPoint(geometry::Pose2{0.0, 0.0, theta}, l.point_m);
      const Eigen::Vector2d t = g.point_m - rotated;
      poses.push_back({t.x(), t.y(), theta});
    }
  }
  return poses;
}

// Scores the candidates coarsely, refines the best and keeps the distinct ones, best first.
std::vector<PlacementHypothesis> Rank(std::vector<geometry::Pose2> candidates,
                                      const std::vector<PlacementHypothesis>& previous,
                                      const Samples& samples, const DistanceField& field,
                                      const PlacementOptions& options) {
  std::vector<std::pair<double, std::size_t>> coarse;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    coarse.emplace_back(-field.Score(samples, candidates[i], options.score_distance_m,
                                     kCoarseStride), i);
  }
  std::sort(coarse.begin(), coarse.end());
  std::vector<geometry::Pose2> refined_from;
  for (std::size_t i = 0; i < std::min(kCoarseKept, coarse.size()); ++i) {
    refined_from.push_back(candidates[coarse[i].second]);
  }
  for (const PlacementHypothesis& old : previous) refined_from.push_back(old.map_from_entity);
  std::vector<PlacementHypothesis> refined;
  for (const geometry::Pose2& pose : refined_from) {
    refined.push_back(Refine(pose, samples, field, options.score_distance_m));
  }
  std::sort(refined.begin(), refined.end(), Better);
  std::vector<PlacementHypothesis> distinct;
  for (const PlacementHypothesis& hypothesis : refined) {
    if (static_cast<int>(distinct.size()) >= options.max_hypotheses) break;
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const auto& kept) {
      return Same(kept.map_from_entity, hypothesis.map_from_entity, options);
    });
    if (!seen && hypothesis.score > 0.0) distinct.push_back(hypothesis);
  }
  return distinct;
}

std::string Percent(double fraction) {
  return std::to_string(static_cast<int>(std::lround(100.0 * fraction))) + "%";
}

std::string Metres(double value_m) {
  const long decimetres = std::lround(value_m * 10.0);
  return std::to_string(decimetres / 10) + "." + std::to_string(std::abs(decimetres % 10)) + " m";
}

// The winner to sub-cell accuracy: the distance field is quantised to grid_resolution_m, so the
// correlation matcher's least-squares refinement (exact nearest neighbours) finishes the job.
geometry::Pose2 Polish(const geometry::Pose2& map_from_entity, const Samples& local,
                       const std::vector<line_map::LineSegment>& global,
                       const PlacementOptions& options) {
  const Samples reference = detail::SampleWalls(global, options.grid_resolution_m);
  const scan_matching::CorrelationScanMatcher matcher({options.score_distance_m / 2.0, 0.02, 8, 10, true},
                                                      reference.points_m);
  const scan_matching::SearchWindow window{4 * options.grid_resolution_m, 4 * options.grid_resolution_m,
                                           0.03490658503988659, 0.02, 0.004363323129985824};
  const scan_matching::MatchResult match = matcher.MatchExhaustive(local.points_m, map_from_entity, window);
  return match.converged ? match.reference_from_scan : map_from_entity;
}

// Whether the winner's margin over another hypothesis could be chance: were the two equally
// good, what would their margin's sd be? Each local wall is one piece of evidence (its points move
// together), its vote the difference d_i of what the two explain of it; for two equally good
// poses each vote's sign is a coin toss, so the margin sum d_i has sd sqrt(sum d_i^2) (a sign
// test weighted by the votes). A corridor alias that differs from the winner by one dead end has a
// small sd; a pose that explains other walls than the winner's (a building turned by 90 deg, whose
// corridors fit as well) a large one. Returns the other hypothesis the winner beats by the
// smallest number of sds, and that margin and sd.
struct Contest {
  double margin_m = 0.0;
  double sd_m = 0.0;
};

Contest ClosestContest(const std::vector<PlacementHypothesis>& hypotheses, const Samples& samples,
                       std::size_t walls, const DistanceField& field, double score_distance_m) {
  const std::vector<double> best = field.ExplainedPerWall(
      samples, walls, hypotheses.front().map_from_entity, score_distance_m);
  Contest closest{hypotheses.size() > 1 ? hypotheses.front().explained_m - hypotheses[1].explained_m
                                        : hypotheses.front().explained_m,
                  0.0};
  double closest_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t h = 1; h < hypotheses.size(); ++h) {
    const std::vector<double> other =
        field.ExplainedPerWall(samples, walls, hypotheses[h].map_from_entity, score_distance_m);
    Contest contest;
    double sum_sq_m2 = 0.0;
    for (std::size_t i = 0; i < walls; ++i) {
      contest.margin_m += best[i] - other[i];
      sum_sq_m2 += (best[i] - other[i]) * (best[i] - other[i]);
    }
    contest.sd_m = std::sqrt(sum_sq_m2);
    const double ratio = contest.sd_m > 0.0 ? contest.margin_m / contest.sd_m
                                            : std::numeric_limits<double>::infinity();
    if (ratio < closest_ratio) {
      closest_ratio = ratio;
      closest = contest;
    }
  }
  return closest;
}

// Sets placed, margin and reason from the ranked hypotheses.
void Decide(PlacementResult& result, const Samples& samples, std::size_t walls,
            const DistanceField& field, const PlacementOptions& options) {
  if (result.hypotheses.empty()) {
    result.reason = "no corner of the local map matches one of the global map";
    return;
  }
  const PlacementHypothesis& best = result.hypotheses.front();
  const double runner_up_m = result.hypotheses.size() > 1 ? result.hypotheses[1].explained_m : 0.0;
  result.margin_m = best.explained_m - runner_up_m;
  const Contest contest =
      ClosestContest(result.hypotheses, samples, walls, field, options.score_distance_m);
  if (best.score < options.min_score) {
    result.reason = "the best hypothesis explains only " + Percent(best.score) + " of the walls";
  } else if (result.margin_m < options.min_margin_m) {
    result.reason = "aliased: " + std::to_string(result.hypotheses.size()) +
                    " hypotheses, the best explains only " + Metres(result.margin_m) +
                    " of wall more than the next";
  } else if (contest.margin_m <= options.min_margin_sd * contest.sd_m) {
    result.reason = "aliased: the best explains " + Metres(contest.margin_m) +
                    " of wall more than a pose that explains other walls, chance alone " +
                    Metres(contest.sd_m) + " (sd, wall by wall)";
  } else {
    result.placed = true;
    result.map_from_entity = best.map_from_entity;
  }
}

}  // namespace

void ValidatePlacementOptions(const PlacementOptions& o) {
  using detail::Require;
  const auto positive = [](double value) { return std::isfinite(value) && value > 0.0; };
  Require(positive(o.sample_spacing_m), "placement.sample_spacing_m must be > 0 (metres)",
          o.sample_spacing_m);
  Require(positive(o.score_distance_m), "placement.score_distance_m must be > 0 (metres)",
          o.score_distance_m);
  Require(positive(o.grid_resolution_m) && o.grid_resolution_m <= o.score_distance_m,
          "placement.grid_resolution_m must be in (0, score_distance_m] (metres)",
          o.grid_resolution_m);
  Require(positive(o.corner_max_gap_m), "placement.corner_max_gap_m must be > 0 (metres)",
          o.corner_max_gap_m);
  Require(positive(o.min_corner_angle_rad) && o.min_corner_angle_rad < std::numbers::pi / 2,
          "placement.min_corner_angle_rad must be in (0, pi/2) (radians)", o.min_corner_angle_rad);
  Require(positive(o.corner_angle_tolerance_rad),
          "placement.corner_angle_tolerance_rad must be > 0 (radians)",
          o.corner_angle_tolerance_rad);
  Require(o.max_local_segments >= 2, "placement.max_local_segments must be >= 2 (count)",
          o.max_local_segments);
  Require(o.max_global_segments >= 2, "placement.max_global_segments must be >= 2 (count)",
          o.max_global_segments);
  Require(o.max_hypotheses >= 1, "placement.max_hypotheses must be >= 1 (count)",
          o.max_hypotheses);
  Require(positive(o.distinct_distance_m), "placement.distinct_distance_m must be > 0 (metres)",
          o.distinct_distance_m);
  Require(positive(o.distinct_angle_rad), "placement.distinct_angle_rad must be > 0 (radians)",
          o.distinct_angle_rad);
  Require(std::isfinite(o.min_local_length_m) && o.min_local_length_m >= 0.0,
          "placement.min_local_length_m must be >= 0 (metres)", o.min_local_length_m);
  Require(o.min_score > 0.0 && o.min_score <= 1.0, "placement.min_score must be in (0, 1]",
          o.min_score);
  Require(std::isfinite(o.min_margin_m) && o.min_margin_m >= 0.0,
          "placement.min_margin_m must be >= 0 (metres)", o.min_margin_m);
  Require(std::isfinite(o.min_margin_sd) && o.min_margin_sd >= 0.0,
          "placement.min_margin_sd must be >= 0 (standard deviations)", o.min_margin_sd);
}

PlacementResult PlaceLocalMap(const std::vector<line_map::LineSegment>& local,
                              const std::vector<line_map::LineSegment>& global,
                              const std::vector<PlacementHypothesis>& previous,
                              const PlacementOptions& options) {
  ValidatePlacementOptions(options);
  PlacementResult result;
  const Samples samples = detail::SampleWalls(local, options.sample_spacing_m);
  result.local_length_m = samples.length_m;
  if (samples.length_m < options.min_local_length_m || global.empty()) {
    result.hypotheses = previous;
    result.reason = "the local map holds " + Metres(samples.length_m) + " of walls, placement needs " +
                    Metres(options.min_local_length_m) + " and a global map";
    return result;
  }
  const DistanceField field(global, options.grid_resolution_m, 2.0 * options.score_distance_m);
  result.hypotheses = Rank(CornerPoses(local, global, options), previous, samples, field, options);
  Decide(result, samples, local.size(), field, options);
  if (result.placed) result.map_from_entity = Polish(result.map_from_entity, samples, global, options);
  return result;
}

}  // namespace pena::fusion
