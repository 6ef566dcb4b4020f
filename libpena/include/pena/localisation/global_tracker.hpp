#pragma once
// Global localisation over a short walk (beyond the paper): one scan often fits a wrong place as
// well as the right one, so the hypotheses of repeated whole-plan searches are followed as
// placements of the odometry frame, re-fitted at every keyframe and scored by beam agreement on
// the same kept keyframes, until one leads by a margin (docs/localisation.md, "Global localisation").

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
  double min_travel_m = 6.0;       // ... spread over this many metres walked before a decision
  double decide_margin_beams = 150.0;  // the winner's evidence lead over every other hypothesis, beams
  double min_agreement = 0.7;      // the winner's agreement fraction at the latest keyframe
  double through_weight = 0.0;     // weight of a see-through beam against an agreeing one
  int final_keyframes = 0;         // re-fit the winner on this many latest keyframes at once (0 = off)
  double drop_margin_beams = 400.0;  // hypotheses trailing the leader by more are dropped
  double search_every_m = 2.0;       // a new whole-plan search after this many metres walked
  // Headings searched and kept around the odometry frame's (compass-started), rad; 0: every heading.
  double odom_heading_tolerance_rad = 0.0;
  // Pairwise freeze (0 = off): two tracks are compared only on keyframes of this history where
  // both are on the plan (inside its box, at most boundary_fraction of the returns past it).
  int freeze_history_keyframes = 48;
  double boundary_fraction = 0.25;
  // Freeze only: rank by 0 the smallest pairwise lead, 1 recent evidence (dropped only if behind
  // on both), 2 as 1 and the winner must also lead every other pairwise.
  int freeze_ranking = 2;
  bool answer_on_plan = true;     // freeze only: answer with the evidence leader while off the plan
  int return_fit_keyframes = 4;   // freeze only: re-fit a track back on the plan on this many keyframes
  int min_followed_keyframes = 6; // keyframes a track must be re-fitted at since its search (0 = off)
  double min_decide_return_fraction = 0.5;  // no decision where fewer beams return (smoke; 0 = off)
  int min_decide_return_keyframes = 16;     // ... at any of the latest this many keyframes
};

// One followed hypothesis.
struct Track {
  geometry::Pose2 map_from_odom;   // where the odometry frame sits on the plan if it is right
  geometry::Pose2 map_from_body;   // at the latest keyframe
  double evidence_beams = 0.0;     // agreeing minus see-through beams over the kept keyframes
  double agreement = 0.0;          // agreement fraction at the latest keyframe
  bool walks_through_walls = false; // its path over the kept keyframes crosses a plan wall
  std::vector<double> keyframe_beams;  // pairwise freeze only: evidence per kept keyframe, oldest first
  std::vector<bool> keyframe_on_plan;  // ... and whether the place was on the plan there
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
