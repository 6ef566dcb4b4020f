#pragma once
// Learning where the plan's walls really are: at accepted rounds each segment's returns are
// compared with where the other walls put the entity along its normal, and a segment off by the
// same amount at several rounds is moved there (docs/localisation.md, "Plan adaptation").

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/localisation/plan_openings.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {

// The plan's free wall ends (door jambs, a corridor's end) as references along their walls
// (docs/localisation.md, "Wall ends").
struct PlanEndOptions {
  bool enabled = true;          // a wall drawn off across a corridor's end pulls every round along it
  double join_m = 0.1;          // an end with another segment this near is a corner, not a reference
  double across_m = 0.1;        // returns within this of the wall's line count for its end
  double window_m = 0.6;        // ... within this of the end
  int min_points = 4;           // returns that must run densely up to the end
  double max_gap_m = 0.2;       // largest gap between those returns
  double past_rad = 0.053;      // the laser must see past the end within this bearing (3 deg)
  double past_m = 0.3;          // ... at least this much farther than the end
  // Ends that must agree (RMS misfit <= max_spread_m) on an error >= min_error_m to move a pose back.
  int min_ends = 2;
  double max_spread_m = 0.05;
  double min_error_m = 0.15;
};

// Options of the plan adaptation; validated by PlanAdaptation's (and MapLocaliser's) constructor.
struct PlanAdaptationOptions {
  bool enabled = true;          // docs/localisation.md, "Plan adaptation"
  double association_m = 0.6;   // a return counts for the nearest segment within this (normal) distance
  double end_margin_m = 0.15;   // ... and at least this far inside its ends (corners and door jambs)
  int min_points = 8;           // returns on a segment for it to be measured in a round
  double wall_sigma_m = 0.03;   // one measurement per half wall per round (drawing errors are per wall)
  double prior_sigma_m = 0.02;          // motion prior sd at the round before, m
  double prior_sigma_per_m = 0.03;      // ... growing per metre walked
  double prior_sigma_rad = 0.005;       // heading prior sd, rad
  double prior_sigma_rad_per_m = 0.005; // ... growing per metre walked
  double prior_facing_sigma_m = 0.05;   // the prior counts as a reference facing the wall up to this sd
  // Information the other walls and the prior give on the wall's offset (units of wall_sigma_m);
  // below it nothing else pins that direction down and the wall is not measured.
  double min_other_information = 1.5;
  int min_rounds = 5;           // rounds that measured a segment before it may be moved
  double min_offset_m = 0.15;   // mean offset below which a wall stays (the matcher absorbs less)
  double max_spread_m = 0.08;   // standard deviation of its rounds' offsets above which it stays
  PlanOpeningsOptions openings; // walls drawn across real openings are cut (plan_openings.hpp)
  PlanEndOptions ends;
};

// Throws std::invalid_argument naming the field and unit.
void ValidatePlanAdaptationOptions(const PlanAdaptationOptions& options);

// What an accepted round tells besides its returns.
struct RoundView {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();   // the body's position, map frame
  Eigen::Vector3d correction = Eigen::Vector3d::Zero(); // the round's correction: x, y (map frame), heading
  double walked_m = 0.0;                                // distance since the round before
  double heading_rad = 0.0;  // the body's heading in the map frame (the laser's field of view)
};

// A segment the adaptation moved: its index in the plan and the total move along its normal.
struct SegmentShift {
  int index = 0;
  double offset_m = 0.0;  // along the segment's left normal (direction rotated +90 deg)
  int rounds = 0;         // rounds that measured it when it was last moved
};

// Which ends of a plan segment are references along it (free ends as drawn, not cut openings).
struct SegmentEnds {
  bool start = false;
  bool end = false;
};

// The plan and what was learned about it. Not thread-safe.
class PlanAdaptation {
 public:
  PlanAdaptation(const PlanAdaptationOptions& options, std::vector<geometry::Segment2> plan);

  // One accepted round (returns in the map frame at the corrected pose); true when the plan changed.
  bool Observe(const scan_matching::Points2& map_points, const RoundView& view);

  // The round's translation error (map frame) where >= ends.min_ends wall ends agree, else nullopt.
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
  // One round's returns on one segment, their signed normal distances and per-half medians.
  struct Support {
    scan_matching::Points2 points;
    std::vector<double> residuals_m;
    std::vector<Half> halves;
  };
  // The round's pose error (x, y map frame, heading) from the other walls and the prior;
  // covariance in wall_sigma_m^2.
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
  // The segment's offset where the other walls put the entity; nullopt if they do not pin its normal.
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
