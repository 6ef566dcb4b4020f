#pragma once
// Global localisation over a short walk (beyond the paper): one scan in a corridor whose doors
// repeat every ~6 m, or next to a part the plan gets wrong, often fits a wrong place as well as the
// right one. The tracker keeps the ranked hypotheses of whole-plan searches, each as a placement
// of the odometry frame on the plan, re-fits each at every keyframe (GlobalLocaliser::Verify in a
// narrow window) and scores it by beam agreement summed over all keyframes kept so far. All
// hypotheses are scored on the same keyframes, so a place found by a later search (one is made
// every few metres walked) competes on equal evidence. One wins when it leads every other by a
// margin in beams and fits the latest scan well.

#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::localisation {

// Options; validated by the constructor (messages name field and unit).
struct GlobalTrackerOptions {
  int max_tracks = 30;             // hypotheses followed at once (a search adds up to this many)
  int max_keyframes = 16;          // keyframes kept as evidence (the latest)
  int min_keyframes = 6;           // evidence from at least this many keyframes ...
  // ... spread over this many metres walked before a decision. A corridor whose doors repeat
  // every 6 m, seen where the plan draws a wall off, is otherwise decided on the place 6 m along.
  double min_travel_m = 6.0;
  // The winner's evidence (agreeing minus see-through beams, summed over the keyframes) exceeds
  // every other hypothesis' by this many beams ...
  double decide_margin_beams = 150.0;
  // ... and its path over the kept keyframes crosses no plan wall, and its agreement fraction
  // at the latest keyframe is at least this: outside the plan
  // (office: the annex) the true place scores low and a look-alike could otherwise win.
  double min_agreement = 0.7;
  // Weight of a see-through beam (the real beam passed where the plan has a wall) against an
  // agreeing one. 0: a plan that lacks a passage (office: the west wing, the annex) would
  // otherwise push the true place away from its mistakes onto a look-alike 6 m along.
  double through_weight = 0.0;
  // Final fit (0 = off): the winner is re-fitted on the points of the latest this many kept
  // keyframes at once, placed by the odometry (GlobalLocaliser::FitMerged). One keyframe in a
  // corridor pins the pose across it only; door frames spread over a few metres also pin it
  // along. Off: it also pulls good anchors towards walls the plan draws off.
  int final_keyframes = 0;
  double drop_margin_beams = 400.0;  // hypotheses trailing the leader by more are dropped
  double search_every_m = 2.0;       // a new whole-plan search after this many metres walked
  // The odometry frame's heading is the map's to within this (a compass keeps the frame's
  // heading absolute; LocalisationChain starts it at the compass heading): searches look only at
  // headings this close to the odometry's, and tracks whose placement turns the frame by more
  // are dropped. 0: no heading is known, every heading is searched.
  double odom_heading_tolerance_rad = 0.0;
  // Pairwise freeze (0 = off): keyframes kept for comparing tracks pair by pair. When on, two
  // tracks are compared only on keyframes where both are "on the plan" (inside its bounding box
  // and seeing past its boundary on at most boundary_fraction of the returns), on the latest
  // max_keyframes such keyframes of this history: while either is off the plan the pair's
  // difference is frozen, and it resumes when both are on it again: walking past a plan's end
  // wall into an unmapped wing, the true place sees past the wall and a look-alike earns more.
  // Tracks are then ranked by their smallest pairwise lead; the winner leads every other by
  // decide_margin_beams; tracks trailing the leader by drop_margin_beams are dropped unless off
  // the plan at the latest keyframe; a track off the plan is carried by the odometry, not re-fitted.
  // It works together with the three options below and the chain's compass bound; alone it helps
  // where the walker leaves the plan through a wall it draws, and costs where the plan lacks rooms.
  int freeze_history_keyframes = 48;
  double boundary_fraction = 0.25;
  // With the pairwise freeze only: how tracks are ranked and decided.
  //  0: by the smallest pairwise lead (above);
  //  1: by the evidence over the latest max_keyframes (as without the freeze); a track is dropped
  //     only when the leader leads it by drop_margin_beams both on that evidence and pairwise
  //     (and it is on the plan at the latest keyframe); decisions as without the freeze;
  //  2: as 1, and the leader must also lead every other track pairwise by decide_margin_beams.
  // Off the plan the true place may lead on recent evidence while a look-alike leads pairwise, and
  // the other way round elsewhere, so 2 asks for both.
  int freeze_ranking = 2;
  // With the pairwise freeze only (false = off): the answer before a decision (the first of
  // TrackerUpdate::ranked) is the evidence leader when it is off the plan at the latest keyframe,
  // else the pairwise leader (the track with the best smallest pairwise lead).
  bool answer_on_plan = true;
  // With the pairwise freeze only (0 = off): a track back on the plan after being carried off it
  // is re-fitted on the points of its latest this many keyframes at once (FitMerged, final_window):
  // carried by the odometry, the true place drifts 0.3-0.4 m along the annex passage.
  int return_fit_keyframes = 4;
  // A track is decided only after it has been followed (re-fitted) over this many keyframes since
  // the search that found it (0 = off): its evidence on the earlier keyframes is the odometry's
  // replay, which a place found while the true one is off the plan wins without having been
  // checked on a single new scan (office: the north-east room found on walking into the annex).
  // 6, as min_keyframes: fewer lets such a room be decided before the walk refutes it.
  int min_followed_keyframes = 6;
  // No decision at a keyframe where fewer than this fraction of the beams return (0 = off): a scan
  // that sees little of the building (smoke: 20-39 % of the beams return) fits many places.
  double min_decide_return_fraction = 0.5;
  // ... at any of the latest this many keyframes (1: the latest only). 16, max_keyframes, covers
  // the whole evidence window: a decision just after the smoke would rest on evidence gathered
  // in it.
  int min_decide_return_keyframes = 16;
};

// One followed hypothesis.
struct Track {
  geometry::Pose2 map_from_odom;   // where the odometry frame sits on the plan if it is right
  geometry::Pose2 map_from_body;   // at the latest keyframe
  double evidence_beams = 0.0;     // agreeing minus see-through beams over the kept keyframes
  double agreement = 0.0;          // agreement fraction at the latest keyframe
  bool walks_through_walls = false; // its path over the kept keyframes crosses a plan wall
  // Pairwise freeze only: per kept keyframe (oldest first), evidence in beams and whether the
  // place is on the plan there (inside its box, seeing little past its boundary).
  std::vector<double> keyframe_beams;
  std::vector<bool> keyframe_on_plan;
  double pairwise_margin_beams = 0.0;  // its smallest lead over any other (pairwise freeze only)
  bool on_plan = true;                 // on the plan at the latest keyframe (pairwise freeze only)
  int followed_keyframes = 0;          // keyframes it was re-fitted at since its search found it
};

// What one update concluded.
struct TrackerUpdate {
  bool searched = false;                 // a whole-plan search ran at this scan
  std::optional<PoseHypothesis> decided; // the winner at this scan (body pose on the plan)
  GlobalResult ranked;                   // the tracks as hypotheses, best evidence first
};

// Follows global hypotheses of one entity until one wins. Not thread-safe.
class GlobalTracker {
 public:
  // `localiser` must outlive the tracker.
  explicit GlobalTracker(const GlobalLocaliser& localiser, const GlobalTrackerOptions& options = {});

  // Feeds a keyframe scan with the odometry pose it was taken at (any fixed odometry frame).
  TrackerUpdate Update(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body);

  const std::vector<Track>& tracks() const { return tracks_; }
  int searches() const { return searches_; }

 private:
  struct Keyframe {
    sensors::LaserScan scan;
    geometry::Pose2 odom_from_body;
    bool sees_little = false;  // fewer returns than min_decide_return_fraction of the beams
  };

  void Search(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body);
  void Refit(Track& t, const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body) const;
  bool OnPlan(const BeamAgreement& a, const geometry::Pose2& map_from_body) const;
  void Score();
  void Prune();
  void RankPairwise();
  double PairLead(const Track& a, const Track& b) const;
  std::optional<PoseHypothesis> Decide() const;
  geometry::Pose2 FinalFit(const Track& winner) const;
  geometry::Pose2 MergedFit(const geometry::Pose2& map_from_body, int keyframes) const;
  const Track* PairwiseLeader() const;
  GlobalResult Ranked() const;

  const GlobalLocaliser* localiser_;
  GlobalTrackerOptions options_;
  std::vector<Track> tracks_;
  std::vector<Keyframe> keyframes_;
  double travel_m_ = 0.0;
  double since_search_m_ = 0.0;
  int searches_ = 0;
};

}  // namespace pena::localisation
