#pragma once
// Lost and found on an a priori plan (beyond the paper): the entity is judged lost from evidence
// (plan rounds failing while the plan explains little of the scan where the entity is thought to
// be, or the odometry's position spread since the last good round grown past a bound), and then
// searched for globally, first in a region around where it is thought to be that grows with each
// search, then over the whole plan, until a place is found where the plan explains the scan on
// several keyframes in a row (as AMCL's recovery and Cartographer's global constraint search do).

#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::localisation {

// Options; validated by the constructor (messages name field and unit).
struct LostAndFoundOptions {
  bool enabled = true;
  // Lost: lost_after_rounds plan rounds in a row failed while the plan explains (beam agreement,
  // GlobalLocaliser::Agreement) less than lost_explained_fraction of the scan at the pose ...
  int lost_after_rounds = 3;
  double lost_explained_fraction = 0.5;
  // ... or a round failed with the odometry's position sigma since the last good round above this.
  double lost_sigma_m = 2.0;
  // Search: a region of region_start_m radius around the pose on odometry, times region_growth at
  // each search, the whole plan once it covers the plan's box; one search per search_every_m walked.
  double region_start_m = 3.0;
  double region_growth = 2.0;
  double search_every_m = 1.0;
  int max_candidates = 5;  // hypotheses taken from each search
  // Found: a candidate moved by the odometry is re-fitted at each keyframe; it is taken after
  // confirm_keyframes keyframes in a row on which the plan explains at least
  // found_explained_fraction of the scan there, found_margin more than at the lost pose.
  int confirm_keyframes = 3;
  double found_explained_fraction = 0.65;
  double found_margin = 0.1;
};

// What one keyframe did to the lost-and-found state.
struct LostStep {
  bool lost = false;                            // lost after this keyframe
  bool became_lost = false;                     // judged lost at this keyframe
  std::optional<geometry::Pose2> found;         // found here: the body pose on the plan
  bool found_by_round = false;                  // a plan round re-acquired it on its own
  double explained = 0.0;                       // beam agreement at the pose (when computed)
  std::optional<double> searched_radius_m;      // a search ran (0: over the whole plan)
};

// The lost-and-found watch of one entity. Not thread-safe; `global` must outlive it.
class LostAndFound {
 public:
  LostAndFound(const LostAndFoundOptions& options, const GlobalLocaliser& global);

  // One keyframe: its scan, the plan round run at it (nullopt if none), the odometry pose (any
  // fixed odometry frame), the pose on the plan the chain holds now, and the odometry's position
  // sigma since the last accepted round (m).
  LostStep Update(const sensors::LaserScan& scan, const std::optional<MapCorrection>& round,
                  const geometry::Pose2& odom_from_body, const geometry::Pose2& map_from_body,
                  double sigma_since_good_m);

  bool lost() const { return lost_; }

 private:
  // A place the entity may be: its pose on the plan at the odometry pose it was fitted at.
  struct Candidate {
    geometry::Pose2 map_from_body;
    geometry::Pose2 odom_from_body;
    int confirmations = 0;
    double agreement = 0.0;
  };
  void Search(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body,
              const geometry::Pose2& map_from_body, LostStep& step);
  std::optional<geometry::Pose2> Confirm(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body,
                                         double explained_here);

  LostAndFoundOptions options_;
  const GlobalLocaliser* global_;
  bool lost_ = false;
  int bad_rounds_ = 0;
  double radius_m_ = 0.0;          // the next search's region (0: the whole plan)
  double walked_m_ = 0.0;          // since the last search
  bool search_due_ = false;
  std::optional<geometry::Pose2> last_odom_;
  std::vector<Candidate> candidates_;
};

}  // namespace pena::localisation
