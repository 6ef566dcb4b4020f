#pragma once
// Learning where the plan's walls really are (robustness to shifted walls). A rough plan
// draws some walls tens of centimetres off. Where such a wall is the only thing in sight that
// constrains one direction (a corridor's end wall), every round matches the scan onto it and the
// pose follows the drawing. The wall can be measured, though, while other walls pin that
// direction down: at accepted rounds, each segment's real returns are compared with where the
// other walls put the entity along its normal, and a segment that is off by the same amount at
// several rounds is moved there.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/localisation/plan_openings.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {

// The plan's free wall ends (door jambs, a corridor's end) as references along their walls
// (docs/localisation.md, "Wall ends"). An end is measured in a round where the returns along its
// wall's line (within across_m of it, window_m of the end) run densely up to it (the last
// min_points within max_gap_m of each other) and the laser saw past the last one: the nearest
// return beyond it in bearing, within past_rad, lies past_m or more farther away (and its bearing
// is past_rad inside the scan's span).
struct PlanEndOptions {
  // On by default: a wall drawn off across a corridor's end pulls every round along it
  // (docs/localisation.md, "Wall ends").
  bool enabled = true;
  double join_m = 0.1;          // an end with another segment this near is a corner, not a reference
  double across_m = 0.1;
  double window_m = 0.6;
  int min_points = 4;
  double max_gap_m = 0.2;
  double past_rad = 0.053;  // 3 deg
  double past_m = 0.3;
  // A round's corrected pose is moved back when at least min_ends measured ends agree (RMS misfit
  // at most max_spread_m) that it is off by min_error_m or more along the directions they pin
  // down (each end pins its wall's direction; a direction needs min_ends ends' worth).
  int min_ends = 2;
  double max_spread_m = 0.05;
  double min_error_m = 0.15;
};

// Options of the plan adaptation; validated by PlanAdaptation's (and MapLocaliser's) constructor.
struct PlanAdaptationOptions {
  // On by default: measured better on every scenario and no worse on the real logs
  // (docs/localisation.md, "Walls drawn off the plan").
  bool enabled = true;
  double association_m = 0.6;   // a return counts for the nearest segment within this (normal) distance
  double end_margin_m = 0.15;   // ... and at least this far inside its ends (corners and door jambs)
  int min_points = 8;           // returns on a segment for it to be measured in a round
  // How well a wall's position is known from one half of its returns in a round: a drawing
  // error is per wall, so a half counts as one measurement of this, however many returns.
  double wall_sigma_m = 0.03;
  // The motion prior (the pose the odometry predicted for the round) is one more reference: its
  // standard deviation grows with the distance walked since the previous accepted round; while
  // it is at most prior_facing_sigma_m it counts as one of the two references a measured wall
  // needs (min_other_information below).
  double prior_sigma_m = 0.02;
  double prior_sigma_per_m = 0.03;
  double prior_sigma_rad = 0.005;
  double prior_sigma_rad_per_m = 0.005;
  double prior_facing_sigma_m = 0.05;
  // Information from the other walls and the prior on the measured wall's offset, in units of
  // one wall half (wall_sigma_m): below it, nothing else pins that direction down and the wall is
  // not measured (a corridor's end wall seen alone). Two references at least must face the
  // measured wall (normals within 45 deg), and they must agree (max_spread_m): with one, a room
  // drawn too narrow cannot tell which wall is off.
  double min_other_information = 1.5;
  int min_rounds = 5;           // rounds that measured a segment before it may be moved
  // Mean offset below which a wall stays: the matcher's 10 cm hit threshold absorbs such walls,
  // and 0.10 m moved a right wall on team seed 1 ff1 (0.15: no wrong move in 17 runs).
  double min_offset_m = 0.15;
  double max_spread_m = 0.08;   // standard deviation of its rounds' offsets above which it stays
  // Walls drawn across real openings are cut where the rounds see far through them
  // (plan_openings.hpp; docs/localisation.md, "Plan adaptation").
  PlanOpeningsOptions openings;
  PlanEndOptions ends;
};

// Throws std::invalid_argument naming the field and unit.
void ValidatePlanAdaptationOptions(const PlanAdaptationOptions& options);

// What an accepted round tells besides its returns: where the body was (map frame), the
// correction the round applied (x, y in the map frame, heading), and the distance walked since
// the round before it.
struct RoundView {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();
  double walked_m = 0.0;
  double heading_rad = 0.0;  // the body's heading in the map frame (the laser's field of view)
};

// A segment the adaptation moved: its index in the plan and the total move along its normal.
struct SegmentShift {
  int index = 0;
  double offset_m = 0.0;  // along the segment's left normal (direction rotated +90 deg)
  int rounds = 0;         // rounds that measured it when it was last moved
};

// Which ends of a plan segment are references along it: free ends as drawn. An end made by
// cutting an opening is not (it lies on the openings' bin grid).
struct SegmentEnds {
  bool start = false;
  bool end = false;
};

// The plan and what was learned about it. Not thread-safe.
class PlanAdaptation {
 public:
  PlanAdaptation(const PlanAdaptationOptions& options, std::vector<geometry::Segment2> plan);

  // One accepted round: the real returns in the map frame at the corrected pose, and where the
  // laser was. Returns true when a segment was moved or cut (the caller re-casts from the new
  // plan).
  bool Observe(const scan_matching::Points2& map_points, const RoundView& view);

  // Where the plan's free wall ends put a round taken at `origin_m` facing `heading_rad`, whose
  // returns in the map frame are `map_points`: the translation error of that pose (map frame;
  // zero across directions the ends do not pin down) when at least ends.min_ends agree;
  // nullopt otherwise.
  std::optional<Eigen::Vector2d> ErrorAtEnds(const scan_matching::Points2& map_points, const Eigen::Vector2d& origin_m,
                                             double heading_rad) const;

  const std::vector<geometry::Segment2>& plan() const { return plan_; }
  // The segments moved so far, in the order they were first moved.
  const std::vector<SegmentShift>& shifts() const { return shifts_; }
  // The openings cut so far, in order.
  const std::vector<PlanOpening>& openings() const { return openings_.openings(); }

 private:
  struct Evidence {
    std::vector<double> offsets_m;  // one per round that measured the segment
  };
  struct Half {
    Eigen::Vector2d centroid_m;
    double median_m;
  };
  // The returns of one round on one segment, with their signed distances along its normal, and
  // the median of each half along it (filled for segments with min_points returns).
  struct Support {
    scan_matching::Points2 points;
    std::vector<double> residuals_m;
    std::vector<Half> halves;
  };
  // The pose error of the round (x, y in the map frame, heading about the body) where the other
  // walls and the motion prior put it, and its covariance (units: wall_sigma_m^2).
  struct PoseError {
    Eigen::Vector3d error;
    Eigen::Matrix3d covariance;
  };
  // One row of the least squares on the pose error (x, y, heading): d(value) / d(error).
  struct Measurement {
    Eigen::Vector3d row;
    double value_m;
    double weight;
  };

  std::vector<int> SegmentsNear(const scan_matching::Points2& points) const;
  std::vector<Support> Associate(const scan_matching::Points2& points) const;
  static std::vector<Half> Halves(const Support& support, const Eigen::Vector2d& along);
  // nullopt when fewer than two references face the measured segment or they disagree.
  std::optional<PoseError> ErrorFromOthers(int measured, const std::vector<Support>& support,
                                           const RoundView& view) const;
  // The segment's offset where the other walls put the entity; nullopt when they do not pin
  // the pose down along its normal (min_other_information).
  std::optional<double> OffsetAgainstOthers(int measured, const std::vector<Support>& support,
                                            const RoundView& view) const;
  // Keeps ends_ in step with the plan after openings were cut.
  void EndsAfterCuts(const std::vector<PlanOpening>& cuts);
  double PriorSigma(const RoundView& view) const;
  bool Facing(const RoundView& view) const;
  std::vector<Measurement> PriorRows(const RoundView& view) const;
  // Adds one round's offset of a segment; moves it when min_rounds agree. True when moved.
  bool Weigh(int segment, double offset_m);
  bool OnOneLine(int a, int b) const;
  void Move(int index, double offset_m, int rounds);

  PlanAdaptationOptions options_;
  std::vector<geometry::Segment2> plan_;
  std::vector<Evidence> evidence_;
  std::vector<SegmentShift> shifts_;
  PlanOpenings openings_;
  std::vector<SegmentEnds> ends_;  // per segment of plan_
};

}  // namespace pena::localisation
