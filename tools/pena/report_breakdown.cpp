#include "report_breakdown.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "cli_support.hpp"

namespace pena::cli {
namespace {

// The provenance keys of a global-map row (last extra column, space separated).
std::vector<std::string> Keys(const io::LineRow& row) {
  std::stringstream stream(row.extra.substr(row.extra.rfind(',') + 1));
  std::vector<std::string> keys;
  for (std::string key; stream >> key;) keys.push_back(key);
  return keys;
}

}  // namespace

// A global-map row is observed if some provenance key (last extra column) is not "plan:...".
bool ObservedRow(const io::LineRow& row) {
  const std::string provenance = row.extra.substr(row.extra.rfind(',') + 1);
  std::stringstream keys(provenance);
  for (std::string key; keys >> key;) {
    if (key.rfind("plan:", 0) != 0) return true;
  }
  return false;
}

// Where the imprecise length of the observed global map comes from: the observed segments split
// by provenance (one entity alone, several, confirmed by the plan) and by direction (the team
// building is axis-aligned, so an oblique segment is spurious), each scored alone.
std::vector<MapScore> ProvenanceBreakdown(const std::vector<io::LineRow>& global,
                                          const std::vector<geometry::Segment2>& walls) {
  std::map<std::string, std::vector<geometry::Segment2>> classes;
  for (const io::LineRow& row : global) {
    if (!ObservedRow(row)) continue;
    std::set<std::string> entities;
    bool plan = false;
    for (const std::string& key : Keys(row)) {
      if (key.rfind("plan:", 0) == 0) plan = true;
      else entities.insert(key.substr(0, key.find(':')));
    }
    const Eigen::Vector2d d = row.segment.end_m - row.segment.start_m;
    const double off_axis = std::abs(std::remainder(std::atan2(d.y(), d.x()), std::numbers::pi / 2));
    if (off_axis > 10.0 * std::numbers::pi / 180) classes["oblique (> 10 deg off the x/y axes)"].push_back(row.segment);
    if (plan) classes["confirmed by the plan"].push_back(row.segment);
    classes[entities.size() == 1 ? "seen by " + *entities.begin() + " alone"
                                 : "seen by 2+ entities"].push_back(row.segment);
  }
  std::vector<MapScore> out;
  for (const auto& [name, segments] : classes) {
    out.push_back({name, eval::EvaluateLineMap(segments, walls)});
  }
  return out;
}

// The breakdown table: imprecise length (map length not within 0.10 m of an observed wall).
std::string BreakdownTable(const std::vector<MapScore>& breakdown, double total_imprecise_m) {
  std::ostringstream md;
  md << "\n## Where the imprecise length comes from (observed global map)\n\n"
        "A segment is in one provenance class and possibly also in \"confirmed by the plan\" and "
        "\"oblique\". Imprecise = map length farther than 0.10 m from every observed wall.\n\n"
        "| class | segments | length m | imprecise m | share of all imprecise | precision |\n"
        "|---|---|---|---|---|---|\n";
  for (const MapScore& m : breakdown) {
    const double imprecise = std::max(0.0, m.summary.map_length_m - m.summary.precise_length_m);
    md << "| " << m.name << " | " << m.summary.map_segments << " | "
       << Fixed(m.summary.map_length_m, 1) << " | " << Fixed(imprecise, 1) << " | "
       << Fixed(total_imprecise_m > 0 ? 100 * imprecise / total_imprecise_m : 0.0, 1) << "% | "
       << Fixed(100 * m.summary.precision, 1) << "% |\n";
  }
  return md.str();
}

}  // namespace pena::cli
