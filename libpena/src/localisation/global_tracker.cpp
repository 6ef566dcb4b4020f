#include "pena/localisation/global_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "global_tracker", field, rule, value);
}

void Validate(const GlobalTrackerOptions& o) {
  Require(o.max_tracks >= 1, "max_tracks", ">= 1", o.max_tracks);
  Require(o.max_keyframes >= 1, "max_keyframes", ">= 1", o.max_keyframes);
  Require(o.min_keyframes >= 1 && o.min_keyframes <= o.max_keyframes, "min_keyframes",
          "in [1, max_keyframes]", o.min_keyframes);
  Require(o.min_travel_m >= 0.0, "min_travel_m", ">= 0 m", o.min_travel_m);
  Require(o.decide_margin_beams >= 0.0, "decide_margin_beams", ">= 0", o.decide_margin_beams);
  Require(o.drop_margin_beams > o.decide_margin_beams, "drop_margin_beams", "> decide_margin_beams",
          o.drop_margin_beams);
  Require(o.search_every_m > 0.0, "search_every_m", "> 0 m", o.search_every_m);
  Require(o.through_weight >= 0.0, "through_weight", ">= 0", o.through_weight);
  Require(o.final_keyframes >= 0, "final_keyframes", ">= 0", o.final_keyframes);
  Require(o.freeze_history_keyframes >= 0, "freeze_history_keyframes", ">= 0", o.freeze_history_keyframes);
  Require(o.boundary_fraction >= 0.0 && o.boundary_fraction <= 1.0, "boundary_fraction", "in [0, 1]",
          o.boundary_fraction);
  Require(o.freeze_ranking >= 0 && o.freeze_ranking <= 2, "freeze_ranking", "in [0, 2]", o.freeze_ranking);
  Require(o.return_fit_keyframes >= 0, "return_fit_keyframes", ">= 0", o.return_fit_keyframes);
  Require(o.min_followed_keyframes >= 0, "min_followed_keyframes", ">= 0", o.min_followed_keyframes);
  Require(o.min_decide_return_fraction >= 0.0 && o.min_decide_return_fraction <= 1.0, "min_decide_return_fraction",
          "in [0, 1]", o.min_decide_return_fraction);
  Require(o.min_decide_return_keyframes >= 1, "min_decide_return_keyframes", ">= 1", o.min_decide_return_keyframes);
  Require(o.odom_heading_tolerance_rad >= 0.0, "odom_heading_tolerance_rad", ">= 0 rad",
          o.odom_heading_tolerance_rad);
}

bool ByEvidence(const Track& a, const Track& b) { return a.evidence_beams > b.evidence_beams; }

}  // namespace

GlobalTracker::GlobalTracker(const GlobalLocaliser& localiser, const GlobalTrackerOptions& options)
    : localiser_(&localiser), options_(options) {
  Validate(options);
}

// Whole-plan search; its hypotheses not already followed become new tracks.
void GlobalTracker::Search(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body) {
  ++searches_;
  since_search_m_ = 0.0;
  std::optional<HeadingBound> bound;
  if (options_.odom_heading_tolerance_rad > 0.0) {
    bound = HeadingBound{odom_from_body.theta_rad, options_.odom_heading_tolerance_rad};
  }
  const GlobalResult result = localiser_->Localise(scan, options_.max_tracks, bound);
  const geometry::Pose2 body_from_odom = geometry::Inverse(odom_from_body);
  for (const PoseHypothesis& h : result.hypotheses) {
    const bool followed = std::any_of(tracks_.begin(), tracks_.end(), [&](const Track& t) {
      return SamePlace(t.map_from_body, h.map_from_body);
    });
    if (followed) continue;
    Track track;
    track.map_from_odom = geometry::Compose(h.map_from_body, body_from_odom);
    track.map_from_body = h.map_from_body;
    track.agreement = h.agreement;
    tracks_.push_back(track);
  }
}

// Every track on every kept keyframe, at the placement its latest fit gives: the evidence over the
// latest max_keyframes and, for the pairwise freeze, each keyframe's beams and on-plan flag.
void GlobalTracker::Score() {
  const std::size_t recent = std::min(keyframes_.size(), static_cast<std::size_t>(options_.max_keyframes));
  const std::size_t first_recent = keyframes_.size() - recent;
  const bool pairwise = options_.freeze_history_keyframes > 0;
  for (Track& t : tracks_) {
    t.evidence_beams = 0.0;
    t.walks_through_walls = false;
    t.keyframe_beams.clear();
    t.keyframe_on_plan.clear();
    std::optional<geometry::Pose2> previous;
    for (std::size_t i = pairwise ? 0 : first_recent; i < keyframes_.size(); ++i) {
      const geometry::Pose2 map_from_body = geometry::Compose(t.map_from_odom, keyframes_[i].odom_from_body);
      const BeamAgreement a = localiser_->Agreement(keyframes_[i].scan, map_from_body);
      const double beams = a.agree - options_.through_weight * a.through;
      if (pairwise) {
        t.keyframe_beams.push_back(beams);
        t.keyframe_on_plan.push_back(OnPlan(a, map_from_body));
      }
      if (i < first_recent) continue;
      t.evidence_beams += beams;
      if (previous && localiser_->Blocked(*previous, map_from_body)) t.walks_through_walls = true;
      previous = map_from_body;
    }
  }
}

// How far `a` leads `b` (beams) on the latest max_keyframes keyframes where both are on the plan:
// a keyframe where either sees past the plan's boundary or is outside it leaves the lead as it was.
// With fewer than min_keyframes such keyframes there is no earlier lead worth keeping (a place
// off the plan almost all along would otherwise never be refuted, or block every decision with a
// lead from one or two keyframes): the evidence over the latest max_keyframes counts.
double GlobalTracker::PairLead(const Track& a, const Track& b) const {
  double lead = 0.0;
  int used = 0;
  for (std::size_t i = a.keyframe_beams.size(); i-- > 0 && used < options_.max_keyframes;) {
    if (!a.keyframe_on_plan[i] || !b.keyframe_on_plan[i]) continue;
    lead += a.keyframe_beams[i] - b.keyframe_beams[i];
    ++used;
  }
  return used >= options_.min_keyframes ? lead : a.evidence_beams - b.evidence_beams;
}

// Pairwise freeze: each track's margin is its smallest lead over any other; best margin first
// (freeze_ranking 0) or best recent evidence first (1, 2).
void GlobalTracker::RankPairwise() {
  for (Track& t : tracks_) {
    t.pairwise_margin_beams = tracks_.size() > 1 ? std::numeric_limits<double>::infinity() : 0.0;
    for (const Track& o : tracks_) {
      if (&o != &t) t.pairwise_margin_beams = std::min(t.pairwise_margin_beams, PairLead(t, o));
    }
  }
  if (options_.freeze_ranking > 0) {
    std::stable_sort(tracks_.begin(), tracks_.end(), ByEvidence);
    return;
  }
  std::stable_sort(tracks_.begin(), tracks_.end(), [](const Track& a, const Track& b) {
    return a.pairwise_margin_beams > b.pairwise_margin_beams;
  });
}

// The track with the best smallest pairwise lead (pairwise freeze; margins from RankPairwise).
const Track* GlobalTracker::PairwiseLeader() const {
  const Track* best = nullptr;
  for (const Track& t : tracks_) {
    if (!best || t.pairwise_margin_beams > best->pairwise_margin_beams) best = &t;
  }
  return best;
}

// One track re-fitted at a new keyframe (Verify). With the pairwise freeze, a place off the plan
// there (outside it, or seeing past its boundary) keeps the placement the odometry carries: a fit
// to a plan that lacks what the scan sees slid the true place 0.2-0.3 m a keyframe in the west
// wing, which changed its evidence on the earlier keyframes too.
void GlobalTracker::Refit(Track& t, const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body) const {
  geometry::Pose2 carried = geometry::Compose(t.map_from_odom, odom_from_body);
  if (options_.freeze_history_keyframes > 0) {
    const BeamAgreement a = localiser_->Agreement(scan, carried);
    const bool was_on_plan = t.on_plan;
    t.on_plan = OnPlan(a, carried);
    if (!t.on_plan) {
      t.map_from_body = carried;
      t.agreement = a.fraction();
      return;
    }
    if (!was_on_plan && options_.return_fit_keyframes > 0) carried = MergedFit(carried, options_.return_fit_keyframes);
  }
  const PoseHypothesis h = localiser_->Verify(scan, carried);
  t.map_from_odom = geometry::Compose(h.map_from_body, geometry::Inverse(odom_from_body));
  t.map_from_body = h.map_from_body;
  t.agreement = h.agreement;
}

bool GlobalTracker::OnPlan(const BeamAgreement& a, const geometry::Pose2& map_from_body) const {
  return localiser_->Inside(map_from_body) && a.beyond <= options_.boundary_fraction * a.returns;
}

// Drops duplicates (two tracks converged on one place), tracks far behind the leader and the
// worst beyond max_tracks.
void GlobalTracker::Prune() {
  const bool pairwise = options_.freeze_history_keyframes > 0;
  if (pairwise) RankPairwise();
  else std::stable_sort(tracks_.begin(), tracks_.end(), ByEvidence);
  std::vector<Track> kept;
  for (const Track& t : tracks_) {
    const auto same = std::find_if(kept.begin(), kept.end(), [&](const Track& k) {
      return SamePlace(k.map_from_body, t.map_from_body);
    });
    const bool duplicate = same != kept.end();
    // One place: it has been followed since the older of the two was found.
    if (duplicate) same->followed_keyframes = std::max(same->followed_keyframes, t.followed_keyframes);
    // Verify's small turns at each keyframe can add up past the heading bound.
    const bool turned = options_.odom_heading_tolerance_rad > 0.0 &&
                        std::abs(geometry::NormalizeAngle(t.map_from_odom.theta_rad)) > options_.odom_heading_tolerance_rad;
    if (!duplicate && !turned) kept.push_back(t);
  }
  if (!kept.empty() && pairwise && options_.freeze_ranking > 0) {
    // Dropped only when trailing the evidence leader both on recent evidence and pairwise.
    const Track leader = kept.front();
    std::erase_if(kept, [&](const Track& t) {
      return t.keyframe_on_plan.back() && leader.evidence_beams - t.evidence_beams > options_.drop_margin_beams &&
             PairLead(leader, t) > options_.drop_margin_beams;
    });
  } else if (!kept.empty() && pairwise) {
    const Track leader = kept.front();
    // A place off the plan now is kept: its comparison resumes when it is back on the plan.
    std::erase_if(kept, [&](const Track& t) {
      return t.keyframe_on_plan.back() && PairLead(leader, t) > options_.drop_margin_beams;
    });
  } else if (!kept.empty()) {
    const double floor = kept.front().evidence_beams - options_.drop_margin_beams;
    std::erase_if(kept, [&](const Track& t) { return t.evidence_beams < floor; });
  }
  if (kept.size() > static_cast<std::size_t>(options_.max_tracks)) kept.resize(static_cast<std::size_t>(options_.max_tracks));
  tracks_ = std::move(kept);
}

// Tracks are sorted by evidence (Prune): the first wins if it leads the second by the margin.
std::optional<PoseHypothesis> GlobalTracker::Decide() const {
  if (tracks_.empty() || static_cast<int>(keyframes_.size()) < options_.min_keyframes ||
      travel_m_ < options_.min_travel_m) {
    return std::nullopt;
  }
  // A scan that sees little fits many places, and so does evidence gathered on it.
  const std::size_t recent = std::min(keyframes_.size(), static_cast<std::size_t>(options_.min_decide_return_keyframes));
  if (std::any_of(keyframes_.end() - static_cast<std::ptrdiff_t>(recent), keyframes_.end(),
                  [](const Keyframe& k) { return k.sees_little; })) {
    return std::nullopt;
  }
  const Track& leader = tracks_.front();
  if (leader.agreement < options_.min_agreement || leader.walks_through_walls ||
      leader.followed_keyframes < options_.min_followed_keyframes) {
    return std::nullopt;
  }
  // The margin is pairwise (freeze_ranking 0), on recent evidence (no freeze, or ranking 1), or
  // both (ranking 2).
  const bool pairwise = options_.freeze_history_keyframes > 0;
  const bool pairwise_margin = pairwise && options_.freeze_ranking != 1;
  const bool evidence_margin = !pairwise || options_.freeze_ranking > 0;
  if (pairwise_margin) {
    for (std::size_t i = 1; i < tracks_.size(); ++i) {
      if (PairLead(leader, tracks_[i]) < options_.decide_margin_beams) return std::nullopt;
    }
  }
  if (evidence_margin && tracks_.size() > 1 &&
      leader.evidence_beams - tracks_[1].evidence_beams < options_.decide_margin_beams) {
    return std::nullopt;
  }
  PoseHypothesis winner;
  winner.map_from_body = options_.final_keyframes > 0 ? FinalFit(leader) : leader.map_from_body;
  winner.agreement = leader.agreement;
  winner.score = leader.agreement;
  return winner;
}

// The latest keyframes' points in the latest body frame (placed by the odometry), fitted at once.
geometry::Pose2 GlobalTracker::FinalFit(const Track& winner) const {
  return MergedFit(winner.map_from_body, options_.final_keyframes);
}

// `map_from_body` (at the latest keyframe) re-fitted on the points of the latest `keyframes` kept
// keyframes, placed in the latest body frame by the odometry.
geometry::Pose2 GlobalTracker::MergedFit(const geometry::Pose2& map_from_body, int keyframes) const {
  const geometry::Pose2 body_from_odom = geometry::Inverse(keyframes_.back().odom_from_body);
  scan_matching::Points2 merged;
  const std::size_t n = std::min(keyframes_.size(), static_cast<std::size_t>(keyframes));
  for (std::size_t i = keyframes_.size() - n; i < keyframes_.size(); ++i) {
    const geometry::Pose2 latest_from_k = geometry::Compose(body_from_odom, keyframes_[i].odom_from_body);
    for (const Eigen::Vector2d& p : scan_matching::ScanToPoints(keyframes_[i].scan, 0.1)) {
      merged.push_back(geometry::TransformPoint(latest_from_k, p));
    }
  }
  return localiser_->FitMerged(merged, map_from_body).map_from_body;
}

GlobalResult GlobalTracker::Ranked() const {
  GlobalResult ranked;
  std::vector<const Track*> order;
  for (const Track& t : tracks_) order.push_back(&t);
  if (options_.freeze_history_keyframes > 0 && options_.answer_on_plan && !tracks_.empty()) {
    // The evidence leader when it is off the plan now, else the pairwise leader, goes first.
    const Track* evidence = &*std::max_element(tracks_.begin(), tracks_.end(), [](const Track& a, const Track& b) {
      return a.evidence_beams < b.evidence_beams;
    });
    const bool on_plan = evidence->keyframe_on_plan.empty() || evidence->keyframe_on_plan.back();
    const Track* answer = on_plan ? PairwiseLeader() : evidence;
    const auto it = std::find(order.begin(), order.end(), answer);
    std::rotate(order.begin(), it, it + 1);
  }
  for (const Track* tp : order) {
    const Track& t = *tp;
    PoseHypothesis h;
    h.map_from_body = t.map_from_body;
    h.agreement = t.agreement;
    h.score = t.evidence_beams;
    ranked.hypotheses.push_back(h);
  }
  const auto& h = ranked.hypotheses;
  ranked.margin = h.size() > 1 ? h[0].score - h[1].score : (h.empty() ? 0.0 : 1.0);
  // With the pairwise freeze the leader's margin is its smallest pairwise lead.
  if (options_.freeze_history_keyframes > 0 && h.size() > 1) ranked.margin = tracks_.front().pairwise_margin_beams;
  return ranked;
}

TrackerUpdate GlobalTracker::Update(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body) {
  const double step_m = keyframes_.empty() ? 0.0
                                           : std::hypot(odom_from_body.x_m - keyframes_.back().odom_from_body.x_m,
                                                        odom_from_body.y_m - keyframes_.back().odom_from_body.y_m);
  travel_m_ += step_m;
  since_search_m_ += step_m;
  const bool sees_little = static_cast<double>(scan.CountReturns()) <
                           options_.min_decide_return_fraction * static_cast<double>(scan.ranges_m.size());
  keyframes_.push_back({scan, odom_from_body, sees_little});
  const int kept = std::max(options_.max_keyframes, options_.freeze_history_keyframes);
  if (keyframes_.size() > static_cast<std::size_t>(kept)) keyframes_.erase(keyframes_.begin());
  // Existing tracks re-fitted at this scan (the odometry carried them here) ...
  for (Track& t : tracks_) {
    Refit(t, scan, odom_from_body);
    ++t.followed_keyframes;
  }
  // ... new places from a whole-plan search when due, then all scored on the same keyframes.
  TrackerUpdate update;
  if (tracks_.empty() || since_search_m_ >= options_.search_every_m) {
    Search(scan, odom_from_body);
    update.searched = true;
  }
  Score();
  Prune();
  update.decided = Decide();
  update.ranked = Ranked();
  return update;
}

}  // namespace pena::localisation
