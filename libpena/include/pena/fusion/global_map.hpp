#pragma once
// The merged global line map of the fusion service: every source (the a priori plan and
// each placed entity's local map, already in the map frame) is merged into one line map with
// line_map::LineMap's same-wall rule; global ids stay stable across rebuilds because each global
// segment is matched to its predecessor by the local segments that support it (provenance).

#include <cmath>
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
  // Rules for walls one entity alone saw: docs/fusion.md, "The global map", step 3.
  double min_lone_support_per_m = 10.0;    // occupied cells per metre a lone wall needs (0 = all published)
  double lone_duplicate_distance_m = 0.8;  // a lone parallel wall this near a corroborated one is its copy, m
  // A lone wall is published while its entity's wall error estimated around it (step 3's noise
  // model) is at most this, m.
  double max_lone_error_m = 0.15;
  double error_radius_m = 10.0;   // how far an entity's compared walls tell about its others, m
  double prior_evidence_m = 5.0;  // wall length the prior (walls within the merge rule) weighs, m
  double plan_shadow_m = 0.6;    // an observed parallel wall this near a plan wall replaces it there, m
  double min_plan_piece_m = 0.3;  // shorter uncovered plan pieces are dropped, m
};

// How an entity's walls compare with the other sources at a rebuild, metres.
struct EntityAgreement {
  double agree_m = 0.0;     // its segments merged into a corroborated wall
  double disagree_m = 0.0;  // its lone drifted copies of one
  double offset_sq_m3 = 0.0;  // sum of length x squared offset from the other sources' wall
  double compared_m() const { return agree_m + disagree_m; }
  // agree_m / compared_m(); 1 when nothing was compared.
  double ratio() const { return compared_m() > 0.0 ? agree_m / compared_m() : 1.0; }
  // Length-weighted RMS offset of its compared walls from the others' (0 when none), m.
  double rms_offset_m() const {
    return compared_m() > 0.0 ? std::sqrt(offset_sq_m3 / compared_m()) : 0.0;
  }
};

// Who saw a published wall and how well it is placed.
struct WallSupport {
  // Entities whose walls are in it or were withheld as its copies, and "plan" if it confirms or
  // is a plan wall; sorted.
  std::vector<std::string> seen_by;
  // Estimated sd of the wall's position error, m: its entities' wall error around it (the noise
  // model of docs/fusion.md step 3), combined over its entities; 0 for a plan-only piece.
  double error_sd_m = 0.0;
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

  // Merges `sources` from scratch; returns the change against the current map (empty: version kept).
  line_map::MapDelta Rebuild(const std::vector<MergeSource>& sources);
  // Each entity's agreement at the last Rebuild (entities with nothing compared are absent).
  const std::map<std::string, EntityAgreement>& agreement() const { return agreement_; }
  // Each published wall's support at the last Rebuild, by id (empty after FromSnapshot until the
  // next Rebuild).
  const std::map<std::int64_t, WallSupport>& support() const { return support_; }

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
  std::map<std::int64_t, WallSupport> support_;       // of the last Rebuild, by published id
};

}  // namespace pena::fusion
