// One search against the plan and what is made of it: the judgement (paper's threshold, the
// weak direction kept from the odometry), re-casting a large correction, and the search along a
// corridor when the odometry's keyframe came from its motion prior.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "map_localiser_impl.hpp"

namespace pena::localisation {
namespace {

// The number of grid poses of a search window.
long Candidates(const scan_matching::SearchWindow& w) {
  const auto side = [](double size, double step) { return 2L * std::lround(0.5 * size / step) + 1; };
  return side(w.size_x_m, w.step_xy_m) * side(w.size_y_m, w.step_xy_m) *
         side(w.size_theta_rad, w.step_theta_rad);
}

// How much eq. 2 falls when the best pose is moved by `probe_m` either way along `direction`
// (body frame): the correlation surface's own evidence that the weak direction is constrained.
double AlongDrop(const scan_matching::CorrelationScanMatcher& matcher, const scan_matching::Points2& real,
                 const geometry::Pose2& best, const Eigen::Vector2d& direction, double probe_m) {
  const double peak = matcher.Score(real, best);
  double side = 0.0;
  for (const double sign : {-1.0, 1.0}) {
    const geometry::Pose2 moved{best.x_m + sign * probe_m * direction.x(),
                                best.y_m + sign * probe_m * direction.y(), best.theta_rad};
    side = std::max(side, matcher.Score(real, moved));
  }
  return peak - side;
}

// Whether the search's best grid position lies inside the window `w`, not on its edge (x, y).
bool InteriorXy(const scan_matching::MatchResult& match, const scan_matching::SearchWindow& w) {
  const geometry::Pose2& g = match.grid_pose;
  return match.converged && std::abs(g.x_m) < 0.5 * (w.size_x_m - w.step_xy_m) &&
         std::abs(g.y_m) < 0.5 * (w.size_y_m - w.step_xy_m);
}

// The same in heading too.
bool Interior(const scan_matching::MatchResult& match, const scan_matching::SearchWindow& w) {
  return InteriorXy(match, w) &&
         std::abs(match.grid_pose.theta_rad) < 0.5 * (w.size_theta_rad - w.step_theta_rad);
}

// Whether `best_score` at `best_along_m` beats by `margin` every place of `scores` (along_m,
// score) at least `gap_m` from it.
bool StandsOut(const std::vector<std::pair<double, double>>& scores, double best_along_m, double best_score,
               double gap_m, double margin) {
  return std::none_of(scores.begin(), scores.end(), [&](const std::pair<double, double>& place) {
    return std::abs(place.first - best_along_m) >= gap_m - 1e-9 && place.second > best_score - margin;
  });
}

}  // namespace

using internal::Found;

// Accepts or rejects a round on the paper's correlation threshold, and keeps the least-squares
// refinement only along directions the scan constrains.
Found MapLocaliser::Impl::Judge(const scan_matching::MatchResult& match,
                                const scan_matching::CorrelationScanMatcher& matcher,
                                const scan_matching::Points2& real, const scan_matching::SearchWindow& searched,
                                MapCorrection& round) const {
  round.score = match.score;
  round.hits = match.hits;
  geometry::Pose2 correction = match.reference_from_scan;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(match.information.topLeftCorner<2, 2>());
  const Eigen::Vector2d values = solver.eigenvalues();  // ascending
  round.constraint_ratio = values(1) > 0.0 ? std::max(0.0, values(0)) / values(1) : 0.0;
  const Eigen::Vector2d weak = solver.eigenvectors().col(0);
  round.weak_axis_rad = std::atan2(weak.y(), weak.x());
  round.along_drop = AlongDrop(matcher, real, correction, weak, options.along_probe_m);
  if (round.constraint_ratio < options.degenerate_eigen_ratio && round.along_drop < options.along_min_drop) {
    // Along a corridor the point-to-line information is weak by construction; the correlation
    // surface tells whether door frames and corridor ends still pin the pose down (the score
    // falls off along the corridor). Where it is flat, a plan wall drawn across an opening
    // could drag the pose: the odometry is kept in the weak direction.
    const Eigen::Vector2d strong = solver.eigenvectors().col(1);
    const Eigen::Vector2d kept = strong * strong.dot(Eigen::Vector2d(correction.x_m, correction.y_m));
    correction.x_m = kept.x();
    correction.y_m = kept.y();
    round.degenerate = true;
  }
  const double min_score =
      status == MapStatus::kOutsideMap ? options.reacquire_min_score : options.min_score;
  // The least-squares refinement after the search is not bounded by the window. It may finish a
  // little beyond it, but a correction more than twice the searched half-extent was not searched
  // for, and taking it may throw the entity off for good.
  const geometry::Pose2& found = match.reference_from_scan;
  const bool in_window = std::abs(found.x_m) <= searched.size_x_m &&
                         std::abs(found.y_m) <= searched.size_y_m &&
                         std::abs(found.theta_rad) <= searched.size_theta_rad;
  round.accepted =
      match.converged && in_window && match.hits >= options.min_hits && match.score >= min_score;
  round.confidence = match.score * std::min(1.0, match.hits / (2.0 * options.min_hits));
  round.correction = round.accepted ? correction : geometry::Pose2{};
  return {correction, weak, in_window && Interior(match, searched), in_window && InteriorXy(match, searched)};
}

std::optional<Found> MapLocaliser::Impl::Search(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                                const geometry::Pose2& map_from_body,
                                                const scan_matching::SearchWindow& searched,
                                                MapCorrection& round) const {
  const scan_matching::Points2 virtual_points = VirtualPoints(scan, map_from_body);
  round.virtual_points = static_cast<int>(virtual_points.size());
  round.accepted = false;
  round.degenerate = false;
  round.correction = {};
  if (real.empty() || virtual_points.size() < static_cast<std::size_t>(options.min_hits)) {
    return std::nullopt;
  }
  const scan_matching::CorrelationScanMatcher matcher(options.matcher, virtual_points);
  // Exhaustive search is cheaper for the paper's small window (no max-grids to build).
  const scan_matching::MatchResult match =
      Candidates(searched) > 20000 ? matcher.MatchBranchAndBound(real, {}, searched)
                                   : matcher.MatchExhaustive(real, {}, searched);
  return Judge(match, matcher, real, searched, round);
}

MapCorrection MapLocaliser::Impl::Recast(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                         const MapCorrection& round, const geometry::Pose2& correction) const {
  MapCorrection again = round;
  const auto refined =
      Search(scan, real, geometry::Compose(round.map_from_body_before, correction), options.window, again);
  again.recast = true;
  again.first_score = round.first_score;
  if (refined && again.accepted) again.correction = geometry::Compose(correction, again.correction);
  return again;
}

std::optional<MapCorrection> MapLocaliser::Impl::AlongSearch(const sensors::LaserScan& scan,
                                                             const scan_matching::Points2& real,
                                                             const MapCorrection& round, const Found& found) const {
  std::optional<MapCorrection> best;
  double best_along_m = 0.0;
  std::vector<std::pair<double, double>> scores;  // (along_m, score) of every place searched
  const int steps = static_cast<int>(std::floor(options.along_search_m / options.along_search_step_m + 1e-9));
  for (int k = -steps; k <= steps; ++k) {
    if (k == 0) continue;
    const double along_m = k * options.along_search_step_m;
    const geometry::Pose2 moved{found.correction.x_m + along_m * found.weak.x(),
                                found.correction.y_m + along_m * found.weak.y(), found.correction.theta_rad};
    MapCorrection candidate = Recast(scan, real, round, moved);
    scores.emplace_back(along_m, candidate.score);
    // Only a place the scan pins down there (door frames, a corridor end) can tell, and it
    // needs the evidence of a re-acquisition: a search this wide errs more (a look-alike more than
    // a metre off can score well below that).
    if (!candidate.accepted || candidate.degenerate || candidate.score < options.reacquire_min_score) continue;
    if (!best || candidate.score > best->score) best = candidate, best_along_m = along_m;
  }
  if (!best || best->score < round.score + options.along_min_drop) return std::nullopt;
  // The place must stand out from the others searched, not only from the expected one: along a
  // passage whose plan fits about as well everywhere, the best of flat scores is a coin toss
  // (two places a metre either way may score within 0.02 of each other).
  if (options.along_search_unique &&
      !StandsOut(scores, best_along_m, best->score, 2.0 * options.along_search_step_m, options.along_min_drop)) {
    return std::nullopt;
  }
  return best;
}

}  // namespace pena::localisation
