#pragma once
// The merged global line map of the fusion service: every source (the a priori plan and
// each placed entity's local map, already in the map frame) is merged into one line map with
// line_map::LineMap's same-wall rule; global ids stay stable across rebuilds because each global
// segment is matched to its predecessor by the local segments that support it (provenance).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "pena/line_map/line_map.hpp"
#include "pena/line_map/line_segment.hpp"
#include "pena/line_map/map_delta.hpp"

namespace pena::fusion {

// One input of the merge: its name ("plan", an entity id) and its segments in the map frame.
struct MergeSource {
  std::string name;
  std::vector<line_map::LineSegment> segments;  // ids are the source's own segment ids
  bool plan = false;  // the a priori plan: laid under the observations, not merged with them
};

// Options of the global map; validated by GlobalMap's constructor.
struct GlobalMapOptions {
  line_map::LineMapOptions merge;  // when walls of different sources are one wall
  // A wall only one entity saw (no other entity, no plan) is published only if it has at least
  // this many occupied grid cells per metre behind it: dotted floor reflections seen through a
  // door by one person (~5 cells/m) stay out until someone corroborates them; a solid wall on a
  // 5 cm grid has 14-20 cells/m per extraction. Cells per metre, >= 0 (0 = publish everything).
  double min_lone_support_per_m = 10.0;
  // A wall only one entity saw that runs parallel (within merge.merge_angle_rad) to a wall
  // several sources corroborate (two entities, or an entity and the plan), at most this far
  // from its line and overlapping it along at least half its own length, is that wall seen
  // from a drifted pose (beyond the merge distance): it is not published (it stays in the
  // entity's local map). Metres, >= 0 (0 = publish them). Two real parallel walls closer than
  // this, one of them seen by a single entity, would lose that one: corridors are wider.
  double lone_duplicate_distance_m = 0.8;
  // A wall only one entity saw is published only if that entity's walls agree with the other
  // sources where they can be compared (EntityAgreement): at least this fraction of the
  // compared length. A firefighter whose pose drifted leaves lone copies of walls others saw
  // right (the duplicates above): its walls nobody else saw are then as suspect, and stay out
  // until someone corroborates them; a robot's walls agree and are published. Unitless, in
  // [0, 1] (0 = publish them all).
  double min_lone_agreement = 0.95;
  // Below this compared length the agreement is unknown and the lone wall is published.
  // Metres, >= 0.
  double min_agreement_evidence_m = 5.0;
  // An observed wall parallel to a plan wall and at most this far from it replaces the plan
  // there (the plan is partly wrong: shifted walls). Metres, >= 0.
  double plan_shadow_m = 0.6;
  // Uncovered plan pieces shorter than this are dropped. Metres, >= 0.
  double min_plan_piece_m = 0.3;
};

// How an entity's walls compare with the other sources at a rebuild: the length of its local
// segments merged into a corroborated wall (two entities, or an entity and the plan) and of those
// that are lone drifted copies of one (lone_duplicate_distance_m). Metres.
struct EntityAgreement {
  double agree_m = 0.0;
  double disagree_m = 0.0;
  double compared_m() const { return agree_m + disagree_m; }
  // agree_m / compared_m(); 1 when nothing was compared.
  double ratio() const { return compared_m() > 0.0 ? agree_m / compared_m() : 1.0; }
};

// Provenance key of a source segment: "<source>:<segment id>" (e.g. "ff1:12", "plan:3").
std::string ProvenanceKey(const std::string& source, std::int64_t segment_id);

// The published global map: versioned, with stable ids; every change is a MapDelta.
class GlobalMap {
 public:
  // Throws std::invalid_argument naming the field for bad options.
  explicit GlobalMap(GlobalMapOptions options = {});
  // Resumes from a published snapshot (ids, version and next id kept); throws like
  // line_map::LineMap::FromSnapshot.
  static GlobalMap FromSnapshot(const line_map::MapSnapshot& snapshot,
                                GlobalMapOptions options = {});

  // Merges `sources` (in the given order) from scratch and returns the change against the
  // current map (empty if nothing changed; then the version stays). Each segment's provenance is
  // the sorted list of the keys of the source segments merged into it. Lone weak walls, lone
  // drifted copies and lone walls of disagreeing entities (see GlobalMapOptions) are left out.
  line_map::MapDelta Rebuild(const std::vector<MergeSource>& sources);
  // Each entity's agreement at the last Rebuild (entities with nothing compared are absent).
  const std::map<std::string, EntityAgreement>& agreement() const { return agreement_; }

  // The published map (segments sorted by id).
  line_map::MapSnapshot Snapshot() const;
  std::uint64_t version() const { return published_.version(); }
  std::size_t size() const { return published_.size(); }
  const GlobalMapOptions& options() const { return options_; }

 private:
  GlobalMapOptions options_;
  line_map::LineMap published_;  // receives its own deltas: what a late joiner rebuilds
  std::int64_t next_id_ = 1;
  std::map<std::string, EntityAgreement> agreement_;  // of the last Rebuild (diagnostics)
};

}  // namespace pena::fusion
