#include "pena/fusion/global_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "plan_overlay.hpp"
#include "wall_evidence.hpp"

namespace pena::fusion {
namespace {

using line_map::LineSegment;

// The source keys among a merged segment's provenance: LineMap also records absorbed ids ("#12")
// of the scratch map, which mean nothing outside one rebuild.
std::vector<std::string> KeysOf(const std::vector<std::string>& provenance) {
  std::vector<std::string> keys;
  for (const std::string& entry : provenance) {
    if (!entry.empty() && entry.front() != '#') keys.push_back(entry);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

// Merges every source segment into a scratch map; order matters only for ties of the refit.
std::vector<LineSegment> MergeAll(const std::vector<MergeSource>& sources,
                                  const line_map::LineMapOptions& options) {
  line_map::LineMap merged(options);
  for (const MergeSource& source : sources) {
    if (source.plan) continue;
    for (const LineSegment& segment : source.segments) {
      LineSegment fresh = segment;
      fresh.provenance.clear();
      merged.Integrate({fresh}, ProvenanceKey(source.name, segment.id));
    }
  }
  std::vector<LineSegment> result = merged.segments();
  for (LineSegment& segment : result) segment.provenance = KeysOf(segment.provenance);
  return result;
}

// For each fresh segment, the published id it continues (0 = none): pairs sharing the most
// supporting keys are matched first, so a wall keeps its id while its support grows or shrinks.
std::vector<std::int64_t> MatchIds(const std::vector<LineSegment>& fresh,
                                   const std::vector<LineSegment>& published) {
  std::unordered_map<std::string, std::int64_t> owner;
  for (const LineSegment& segment : published) {
    for (const std::string& key : segment.provenance) owner.emplace(key, segment.id);
  }
  std::vector<std::tuple<int, std::int64_t, std::size_t>> pairs;  // (-shared, old id, fresh index)
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    std::unordered_map<std::int64_t, int> shared;
    for (const std::string& key : fresh[i].provenance) {
      if (const auto it = owner.find(key); it != owner.end()) ++shared[it->second];
    }
    for (const auto& [id, count] : shared) pairs.emplace_back(-count, id, i);
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::int64_t> ids(fresh.size(), 0);
  std::unordered_map<std::int64_t, bool> taken;
  for (const auto& [negative_count, id, index] : pairs) {
    if (ids[index] != 0 || taken[id]) continue;
    ids[index] = id;
    taken[id] = true;
  }
  return ids;
}

// Each source segment (map frame) by provenance key.
std::unordered_map<std::string, geometry::Segment2> SegmentByKey(
    const std::vector<MergeSource>& sources) {
  std::unordered_map<std::string, geometry::Segment2> segments;
  for (const MergeSource& source : sources) {
    for (const LineSegment& segment : source.segments) {
      segments[ProvenanceKey(source.name, segment.id)] = segment.segment;
    }
  }
  return segments;
}

// The plan under the observations (plan_overlay.hpp), in source order: adds the plan keys to the
// observed walls that confirm a plan wall and returns the uncovered plan pieces.
std::vector<LineSegment> PlanPieces(const std::vector<MergeSource>& sources,
                                    std::vector<LineSegment>& observed,
                                    const GlobalMapOptions& options) {
  std::vector<LineSegment> pieces;
  for (const MergeSource& source : sources) {
    if (!source.plan) continue;
    for (const LineSegment& wall : source.segments) {
      for (LineSegment& piece : detail::OverlayPlanWall(wall, ProvenanceKey(source.name, wall.id),
                                                        observed, options)) {
        pieces.push_back(std::move(piece));
      }
    }
  }
  return pieces;
}

// Copies a wall's support into the published segment (what the console draws confidence from):
// the entities among who saw it, and its error sd on the map's 1 cm quanta.
void CarrySupport(const WallSupport& support, LineSegment& wall) {
  wall.seen_by_entities = static_cast<std::uint32_t>(
      std::count_if(support.seen_by.begin(), support.seen_by.end(),
                    [](const std::string& who) { return who != "plan"; }));
  wall.error_sd_m = support.error_sd_m;
  wall = line_map::QuantiseSegment(std::move(wall));
}

}  // namespace

std::string ProvenanceKey(const std::string& source, std::int64_t segment_id) {
  return source + ":" + std::to_string(segment_id);
}

GlobalMap::GlobalMap(GlobalMapOptions options) : options_(options), published_(options.merge) {
  if (!std::isfinite(options_.min_lone_support_per_m) || options_.min_lone_support_per_m < 0.0) {
    throw std::invalid_argument("global_map.min_lone_support_per_m must be >= 0 (cells per metre), got " +
                                std::to_string(options_.min_lone_support_per_m));
  }
  if (!std::isfinite(options_.error_radius_m) || options_.error_radius_m <= 0.0) {
    throw std::invalid_argument("global_map.error_radius_m must be > 0 (metres), got " +
                                std::to_string(options_.error_radius_m));
  }
  for (const auto& [name, value] : {std::pair{"plan_shadow_m", options_.plan_shadow_m},
                                    std::pair{"lone_duplicate_distance_m",
                                              options_.lone_duplicate_distance_m},
                                    std::pair{"max_lone_error_m", options_.max_lone_error_m},
                                    std::pair{"prior_evidence_m", options_.prior_evidence_m},
                                    std::pair{"min_plan_piece_m", options_.min_plan_piece_m}}) {
    if (!std::isfinite(value) || value < 0.0) {
      throw std::invalid_argument(std::string("global_map.") + name + " must be >= 0 (metres), got " +
                                  std::to_string(value));
    }
  }
}

GlobalMap GlobalMap::FromSnapshot(const line_map::MapSnapshot& snapshot,
                                  GlobalMapOptions options) {
  GlobalMap map(options);
  map.published_ = line_map::LineMap::FromSnapshot(snapshot, options.merge);
  map.next_id_ = snapshot.next_id;
  return map;
}

line_map::MapSnapshot GlobalMap::Snapshot() const {
  line_map::MapSnapshot snapshot = published_.Snapshot();
  snapshot.next_id = next_id_;  // ids of removed segments are never reused
  return snapshot;
}

line_map::MapDelta GlobalMap::Rebuild(const std::vector<MergeSource>& sources) {
  std::vector<LineSegment> fresh = MergeAll(sources, options_.merge);
  // The plan confirms observed walls (their plan keys) before the walls are judged; its pieces
  // are laid under what is left, so a plan wall is shown where a withheld wall was.
  PlanPieces(sources, fresh, options_);
  std::vector<geometry::Segment2> plan;
  for (const MergeSource& source : sources) {
    if (!source.plan) continue;
    for (const LineSegment& wall : source.segments) plan.push_back(wall.segment);
  }
  detail::WallJudgement judgement = detail::JudgeWalls(fresh, SegmentByKey(sources), plan, options_);
  agreement_ = std::move(judgement.agreement);
  const std::vector<LineSegment> plan_pieces = PlanPieces(sources, fresh, options_);
  fresh.insert(fresh.end(), plan_pieces.begin(), plan_pieces.end());
  judgement.support.resize(fresh.size(), WallSupport{{"plan"}, 0.0});
  for (std::size_t i = 0; i < fresh.size(); ++i) CarrySupport(judgement.support[i], fresh[i]);
  const std::vector<LineSegment> old = published_.segments();
  const std::vector<std::int64_t> ids = MatchIds(fresh, old);
  line_map::MapDelta delta;
  delta.from_version = published_.version();
  std::unordered_map<std::int64_t, const LineSegment*> old_by_id;
  for (const LineSegment& segment : old) old_by_id.emplace(segment.id, &segment);
  support_.clear();
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    if (ids[i] == 0) {
      fresh[i].id = next_id_++;
      support_[fresh[i].id] = std::move(judgement.support[i]);
      delta.added.push_back(fresh[i]);
      continue;
    }
    fresh[i].id = ids[i];
    support_[fresh[i].id] = std::move(judgement.support[i]);
    const LineSegment& before = *old_by_id.at(ids[i]);
    old_by_id.erase(ids[i]);
    if (!line_map::SameSegment(before, fresh[i])) delta.changed.push_back(fresh[i]);
  }
  for (const auto& entry : old_by_id) delta.removed.push_back(entry.first);
  const auto by_id = [](const LineSegment& a, const LineSegment& b) { return a.id < b.id; };
  std::sort(delta.added.begin(), delta.added.end(), by_id);
  std::sort(delta.changed.begin(), delta.changed.end(), by_id);
  std::sort(delta.removed.begin(), delta.removed.end());
  delta.to_version = delta.from_version + (delta.empty() ? 0 : 1);
  if (const line_map::ApplyResult result = published_.Apply(delta); !result.ok()) {
    throw std::logic_error("fusion global map: own delta refused: " + result.message);
  }
  return delta;
}

}  // namespace pena::fusion
