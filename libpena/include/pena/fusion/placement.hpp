#pragma once
// Placing an entity whose start pose is unknown: its local map (entity frame) is matched
// to the global map (map frame). Hypotheses come from corner correspondences (two walls meeting at
// a corner fix a rigid transform), each is refined and scored by how much of the local walls the
// global map explains; several distinct hypotheses are kept and one is accepted only when it
// explains more wall than any other by more than chance would, because corridors and symmetric
// buildings alias (docs/fusion.md).

#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::fusion {

// Options of PlaceLocalMap; validated by ValidatePlacementOptions (messages name field and unit).
struct PlacementOptions {
  double sample_spacing_m = 0.10;       // local walls are scored at points this far apart
  double score_distance_m = 0.20;       // a point is explained within this of a global wall (graded)
  double grid_resolution_m = 0.05;      // cell of the global map's distance field
  double corner_max_gap_m = 0.50;       // a corner: the two lines meet within this of both ends
  double min_corner_angle_rad = 0.5235987755982988;      // 30 deg: flatter pairs are no corner
  double corner_angle_tolerance_rad = 0.0872664625997;   // 5 deg between matched corner angles
  int max_local_segments = 40;          // the longest local walls used for corners
  int max_global_segments = 400;        // the longest global walls used for corners
  int max_hypotheses = 8;               // distinct hypotheses kept
  double distinct_distance_m = 1.0;     // hypotheses closer than this (and distinct_angle_rad)
  double distinct_angle_rad = 0.17453292519943295;  // 10 deg ... are one
  double min_local_length_m = 8.0;      // no placement before the local map holds this much wall
  double min_score = 0.6;               // the winner explains at least this fraction of the walls
  double min_margin_m = 1.5;            // ... and this many metres of wall more than the runner-up
  double min_margin_sd = 1.0;           // ... and more than the runner-up by this many sd of the
                                        // margin two equally good poses would show (wall by wall)
};

// Throws std::invalid_argument naming the field and its unit.
void ValidatePlacementOptions(const PlacementOptions& options);

// One candidate alignment of the local map.
struct PlacementHypothesis {
  geometry::Pose2 map_from_entity;
  double score = 0.0;        // explained fraction of the local wall length, in [0, 1]
  double explained_m = 0.0;  // explained local wall length, metres (score x local length)
};

// Where placement stands for one entity (failure is data: pending).
struct PlacementResult {
  bool placed = false;
  std::vector<PlacementHypothesis> hypotheses;  // distinct, best first
  geometry::Pose2 map_from_entity;  // the winner when placed
  double margin_m = 0.0;            // winner's explained_m minus the runner-up's (metres)
  double local_length_m = 0.0;      // wall length of the local map
  std::string reason;               // why pending ("aliased: 3 hypotheses within 0.4 m", ...)
};

// Matches `local` (entity frame) to `global` (map frame). `previous` hypotheses (from an earlier
// call on a smaller local map) are re-scored alongside the new ones, so evidence accumulates as
// the local map grows. Deterministic.
PlacementResult PlaceLocalMap(const std::vector<line_map::LineSegment>& local,
                              const std::vector<line_map::LineSegment>& global,
                              const std::vector<PlacementHypothesis>& previous,
                              const PlacementOptions& options = {});

}  // namespace pena::fusion
