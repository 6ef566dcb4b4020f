#pragma once
// Freiburg-style ground-truth relations (Kuemmerle et al. 2009) from a true trajectory: which
// pose pairs a simulated mission is scored on.

#include <vector>

#include "pena/geometry/trajectory.hpp"

namespace pena::sim {

// Which pairs: every consecutive pair (local accuracy at scan rate) plus, from one anchor pose
// every anchor_every_s, the poses offsets_s later (drift over a few seconds of walking).
struct TruthRelationOptions {
  bool consecutive = true;
  double anchor_every_s = 1.0;
  std::vector<double> offsets_s = {2.0, 4.0};
};

// The relations Between(pose(t1), pose(t2)) for the chosen pairs, sorted by t1 then t2. A pair
// is used when a pose exists within half a second after t1 + offset.
std::vector<geometry::Relation> TruthRelations(const geometry::Trajectory& truth,
                                               const TruthRelationOptions& options = {});

}  // namespace pena::sim
