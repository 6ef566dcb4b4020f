#pragma once
// Openings the plan draws shut (the plan is partly wrong). A rough plan draws some walls
// straight across real passages. The virtual scan then shows a wall where the laser sees far
// through, and the rounds match whatever lies beyond onto it: office seed 7 walking south down the
// passage at x 22, whose south end the plan closes, was pulled 1 m back along it in one round.
// Seen from accepted rounds, returns far beyond such a wall (not just behind it, as behind a wall
// drawn a little off) mark where it is open; a stretch open in several rounds and never seen as
// wall is cut out of the segment.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {

// Options of the cuts (part of PlanAdaptationOptions; validated with them).
struct PlanOpeningsOptions {
  bool enabled = true;
  // A return counts as seen through a wall when its beam crosses the wall and it lies at least
  // this far behind the wall's line. Behind a wall drawn a few tenths off the returns are that
  // far behind it; through an opening they are metres beyond.
  double through_margin_m = 1.0;
  double bin_m = 0.1;          // the wall is judged in stretches of this length
  int min_through_points = 3;  // returns through one segment in a round for the round to count
  int min_rounds = 3;          // rounds that saw through a stretch before it may be cut
  double min_width_m = 0.4;    // narrower open stretches stay (a beam slipping past a door jamb)
  // Returns within this of the wall count as the wall seen there: a stretch seen as wall in more
  // than a third of the rounds that saw through it stays.
  double hit_m = 0.15;
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
