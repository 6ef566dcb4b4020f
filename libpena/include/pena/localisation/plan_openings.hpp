#pragma once
// Openings the plan draws shut. A wall drawn across a real passage makes the rounds match what
// lies beyond onto it and pull the entity back along the passage; returns far beyond such a wall
// in accepted rounds mark where it is open, and a stretch open in several rounds and rarely seen
// as wall is cut out of the segment (docs/localisation.md, "Plan adaptation").

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {

// Options of the cuts (part of PlanAdaptationOptions; validated with them).
struct PlanOpeningsOptions {
  bool enabled = true;
  double through_margin_m = 1.0; // a return this far behind a wall it crossed is seen through it
  double bin_m = 0.1;          // the wall is judged in stretches of this length
  int min_through_points = 3;  // returns through one segment in a round for the round to count
  int min_rounds = 3;          // rounds that saw through a stretch before it may be cut
  double min_width_m = 0.4;    // narrower open stretches stay (a beam slipping past a door jamb)
  double hit_m = 0.15;         // returns this near are the wall seen (in > 1/3 of the rounds: it stays)
};

// One cut: the segment (its index before the cut), the open stretch along it in metres from its
// start as it was and where that lay on the map, the rounds that saw through it, and the index of
// the part after the opening (-1 when nothing is left beyond it).
struct PlanOpening {
  int index = 0;
  double from_m = 0.0;
  double to_m = 0.0;
  geometry::Segment2 stretch;
  int rounds = 0;
  int added_index = -1;
};

// Throws std::invalid_argument naming the field (prefix plan_adaptation.openings.).
void ValidatePlanOpeningsOptions(const PlanOpeningsOptions& options);

// Not thread-safe. Works on a plan it does not own (PlanAdaptation's).
class PlanOpenings {
 public:
  explicit PlanOpenings(const PlanOpeningsOptions& options);

  // One accepted round: the returns in the map frame and where the laser was. Cuts open
  // stretches out of `plan` (the part after an opening is appended) and returns the cuts made.
  std::vector<PlanOpening> Observe(const scan_matching::Points2& map_points, const Eigen::Vector2d& origin_m,
                                   std::vector<geometry::Segment2>& plan);

  const std::vector<PlanOpening>& openings() const { return openings_; }

 private:
  // Per stretch of a segment: rounds that saw through it and rounds that saw the wall there;
  // and whether an end of the segment is the edge of an opening cut before (no jamb there).
  struct Bins {
    std::vector<int> through;
    std::vector<int> hits;
    bool open_at_start = false;
    bool open_at_end = false;
  };
  // This round's stretches seen through and seen as wall, per segment.
  struct RoundMarks {
    std::vector<std::vector<bool>> through;
    std::vector<std::vector<bool>> hit;
    std::vector<int> through_points;
  };
  RoundMarks Mark(const scan_matching::Points2& points, const Eigen::Vector2d& origin_m,
                  const std::vector<geometry::Segment2>& plan);
  std::vector<PlanOpening> Cut(std::vector<geometry::Segment2>& plan);
  int BinCount(const geometry::Segment2& segment) const;

  PlanOpeningsOptions options_;
  std::vector<Bins> bins_;  // per segment of the plan
  std::vector<PlanOpening> openings_;
};

}  // namespace pena::localisation
