// One scan matched against the reference: the search (window regrowth), the fallbacks of a poor
// match, the weak-direction and pace checks, the prior gate and the keyframe decision. Split from
// laser_odometry.cpp (style: small files).
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "laser_odometry_impl.hpp"

namespace pena::odometry {

void LaserOdometry::Impl::CheckPace(const Eigen::Matrix3d& information,
                                    const geometry::Pose2& prior) {
  if (!pace_check.enabled() || !motion.last_pose()) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information.topLeftCorner<2, 2>());
  if (!(solver.eigenvalues()(0) < options.pace_check_weak_ratio * solver.eigenvalues()(1))) return;
  const std::optional<Eigen::Vector2d> along =
      pace_check.FallsBehind(*motion.last_pose(), estimate, prior);
  if (!along) return;
  const Eigen::Vector2d to_prior_m(prior.x_m - estimate.x_m, prior.y_m - estimate.y_m);
  const double shift_m = along->dot(to_prior_m);
  estimate.x_m += along->x() * shift_m;
  estimate.y_m += along->y() * shift_m;
  match_weak_direction = along;  // as a degenerate match's: the covariance takes the prior's there
  ++counts.pace_held;
}

scan_matching::MatchResult LaserOdometry::Impl::Search(const scan_matching::Points2& points,
                                                       const geometry::Pose2& prior,
                                                       OdometryEstimate& out) {
  for (;;) {
    const scan_matching::SearchWindow searched = window.Current();
    last_searched = searched;
    out.wide_search = out.wide_search || window.IsWide();
    // Unrefined: Match refines only the search it keeps (a grown window or another prior may win).
    constexpr auto kPolish = scan_matching::Polish::kGridPoseOnly;
    scan_matching::MatchResult result =
        RunMatcher(points, prior, searched, window.IsBase(),
                   window.IsBase() ? OdometryStage::kSearchBase : OdometryStage::kSearchWide,
                   kPolish);
    // A low score or a best pose on the window's edge (the optimum may lie outside): search
    // again at once with a grown window, up to the wide one, before giving up on this scan.
    const bool retry = result.score < options.min_score ||
                       scan_matching::OnWindowEdge(result.grid_pose, prior, searched);
    if (!retry || !window.Grow()) return result;
  }
}

void LaserOdometry::Impl::Match(const scan_matching::Points2& points, OdometryEstimate& out) {
  geometry::Pose2 prior = out.world_from_prior;
  {
    const Timed timed(clock, OdometryStage::kReference);
    // The place choice: back where an earlier keyframe was taken, match against that one again.
    bool rebuild = local_map.ChooseAgain(prior, out.stamp_s);
    if (FillWhileFrozen()) rebuild = local_map.FillFreeSlots() || rebuild;
    if (rebuild) {
      matcher.emplace(options.matcher, local_map.Reference());
    }
  }
  const internal::WindowScale window_before = window;
  scan_matching::MatchResult result = Search(points, prior, out);
  if (result.score < options.local_map_place_fill_below_score) {
    result = SearchFilled(points, prior, window_before, result, out);
  }
  if (result.score < options.min_score) {
    // The motion sensor itself may be wrong (logged odometry that froze, then jumped): try
    // constant velocity and standing still too, and keep the best-scoring hypothesis.
    for (const geometry::Pose2& alternative :
         {geometry::Compose(previous_estimate, velocity), previous_estimate}) {
      scan_matching::MatchResult other = Search(points, alternative, out);
      if (other.score > result.score) {
        result = other;
        prior = alternative;
      }
    }
  }
  counts.wide_searches += out.wide_search ? 1 : 0;
  out.score = result.score;
  if (result.score < options.min_score) {
    out.status = MatchStatus::kFailed;
    ++counts.failed;
    if (out.stale) return;  // a stale scan restarts nothing
    // Lost the reference: restart the local map from this scan at the dead-reckoning pose.
    local_map.Clear();
    TakeKeyframe(points, out);
    return;
  }
  {
    const Timed timed(clock, OdometryStage::kRefinement);
    matcher->Refine(points, result);  // the matcher that found it (SearchFilled may have swapped)
  }
  estimate = result.reference_from_scan;
  match_information = result.information;
  match_reference_covariance = ReferenceCovariance(estimate);  // before a keyframe changes it
  const Eigen::Vector2d travel_m(prior.x_m - previous_estimate.x_m, prior.y_m - previous_estimate.y_m);
  match_weak_direction = weak_check.Apply(result.information, prior, travel_m, estimate);
  if (!match_weak_direction) CheckPace(result.information, prior);
  const bool degenerate = match_weak_direction.has_value();
  out.status = degenerate ? MatchStatus::kDegenerate : MatchStatus::kMatched;
  ++(degenerate ? counts.degenerate : counts.matched);
  if (out.stale) return;  // where the earlier scan was taken: output, but it anchors nothing
  const GateDecision gate = CheckPriorGate(out);
  if (gate == GateDecision::kGated || gate == GateDecision::kRefused) {
    out.gated = true;  // the pose is the match's, but it anchors nothing
    ++counts.gated;
    if (gate == GateDecision::kRefused) {  // not even the pose: the gyro says it is aliased
      out.refused = true;
      ++counts.refused;
      estimate = out.world_from_prior;
      fell_back = true;  // its covariance is the prior's
      match_weak_direction.reset();
    }
    return;
  }
  window.Shrink();
  const geometry::Pose2 moved = geometry::Between(local_map.latest().world_from_body, estimate);
  // A deviation trusted after prior_gate_confirm scans must re-anchor the priors at once: without
  // a keyframe here the next prior is as far off again and is gated again.
  if (gate == GateDecision::kTrusted) {
    gate_trusted = true;
    TakeKeyframe(points, out);
    return;
  }
  if (NearAKeyframe(moved) && result.score >= options.keyframe_min_score) return;
  TakeKeyframe(points, out);
}

}  // namespace pena::odometry
