#pragma once
// pena report's map scores and the breakdown of the global map's imprecise length by provenance
// (docs/demo.md, "Where the imprecise length comes from").

#include <string>
#include <vector>

#include "pena/eval/line_map_error.hpp"
#include "pena/io/line_csv.hpp"

namespace pena::cli {

// One scored map (a table row of the report).
struct MapScore {
  std::string name;
  eval::LineMapErrorSummary summary;
};

// A global-map row is observed if some provenance key (last extra column) is not "plan:...".
bool ObservedRow(const io::LineRow& row);

// The observed rows of a global map split by provenance (one entity alone, several, confirmed by
// the plan) and by direction (> 10 deg off the x/y axes: spurious in an axis-aligned building),
// each class scored alone against `walls` (map frame, metres).
std::vector<MapScore> ProvenanceBreakdown(const std::vector<io::LineRow>& global,
                                          const std::vector<geometry::Segment2>& walls);

// The breakdown as a Markdown section; shares are of `total_imprecise_m` (metres).
std::string BreakdownTable(const std::vector<MapScore>& breakdown, double total_imprecise_m);

}  // namespace pena::cli
