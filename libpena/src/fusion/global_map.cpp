#include "pena/fusion/global_map.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "plan_overlay.hpp"

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

// True for a wall that a single entity saw, with fewer occupied cells per metre than asked.
bool LoneAndWeak(const LineSegment& segment, const GlobalMapOptions& options) {
  const std::string& first = segment.provenance.front();
  const std::string source = first.substr(0, first.rfind(':') + 1);
  const bool lone = source != "plan:" && std::all_of(segment.provenance.begin(), segment.provenance.end(),
                                                     [&source](const std::string& key) {
                                                       return key.compare(0, source.size(), source) == 0;
                                                     });
  return lone && segment.support_cells <
                     options.min_lone_support_per_m * geometry::Length(segment.segment);
}

// The entity sources ("ff1") of a segment's provenance, and whether the plan is among them.
std::pair<std::set<std::string>, bool> SourcesOf(const LineSegment& segment) {
  std::set<std::string> entities;
  bool plan = false;
  for (const std::string& key : segment.provenance) {
    const std::string source = key.substr(0, key.rfind(':'));
    if (source == "plan") {
      plan = true;
    } else {
      entities.insert(source);
    }
  }
  return {entities, plan};
}

// True if `lone` lies along `wall`: parallel, its midpoint within `distance_m` of the wall's
// line, and at least half of it overlapping the wall.
bool Shadowed(const geometry::Segment2& lone, const geometry::Segment2& wall, double angle_rad,
              double distance_m) {
  const Eigen::Vector2d u = lone.end_m - lone.start_m;
  const Eigen::Vector2d v = wall.end_m - wall.start_m;
  const double lone_m = u.norm();
  const double wall_m = v.norm();
  if (lone_m <= 0.0 || wall_m <= 0.0) return false;
  const Eigen::Vector2d along = v / wall_m;
  if (std::abs(along.x() * u.y() - along.y() * u.x()) / lone_m > std::sin(angle_rad)) return false;
  const Eigen::Vector2d mid = 0.5 * (lone.start_m + lone.end_m) - wall.start_m;
  if (std::abs(along.x() * mid.y() - along.y() * mid.x()) > distance_m) return false;
  const double t1 = (lone.start_m - wall.start_m).dot(along);
  const double t2 = (lone.end_m - wall.start_m).dot(along);
  const double overlap_m = std::min(wall_m, std::max(t1, t2)) - std::max(0.0, std::min(t1, t2));
  return overlap_m >= 0.5 * lone_m;
}

// Drops walls a single entity saw that duplicate a corroborated wall (lone_duplicate_distance_m).
void DropLoneDuplicates(std::vector<LineSegment>& fresh, const GlobalMapOptions& options) {
  if (options.lone_duplicate_distance_m <= 0.0) return;
  std::vector<const geometry::Segment2*> corroborated;
  std::vector<bool> lone(fresh.size(), false);
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    const auto [entities, plan] = SourcesOf(fresh[i]);
    if (entities.size() >= 2 || (plan && !entities.empty())) corroborated.push_back(&fresh[i].segment);
    lone[i] = entities.size() == 1 && !plan;
  }
  std::vector<LineSegment> kept;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    const bool duplicate =
        lone[i] && std::any_of(corroborated.begin(), corroborated.end(), [&](const auto* wall) {
          return Shadowed(fresh[i].segment, *wall, options.merge.merge_angle_rad,
                          options.lone_duplicate_distance_m);
        });
    if (!duplicate) kept.push_back(std::move(fresh[i]));
  }
  fresh = std::move(kept);
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
  for (const auto& [name, value] : {std::pair{"plan_shadow_m", options_.plan_shadow_m},
                                    std::pair{"lone_duplicate_distance_m",
                                              options_.lone_duplicate_distance_m},
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
  // The plan goes under the observations (plan_overlay.hpp), in source order.
  std::vector<LineSegment> plan_pieces;
  for (const MergeSource& source : sources) {
    if (!source.plan) continue;
    for (const LineSegment& wall : source.segments) {
      for (LineSegment& piece : detail::OverlayPlanWall(wall, ProvenanceKey(source.name, wall.id),
                                                        fresh, options_)) {
        plan_pieces.push_back(std::move(piece));
      }
    }
  }
  std::erase_if(fresh, [this](const LineSegment& segment) { return LoneAndWeak(segment, options_); });
  DropLoneDuplicates(fresh, options_);
  fresh.insert(fresh.end(), plan_pieces.begin(), plan_pieces.end());
  const std::vector<LineSegment> old = published_.segments();
  const std::vector<std::int64_t> ids = MatchIds(fresh, old);
  line_map::MapDelta delta;
  delta.from_version = published_.version();
  std::unordered_map<std::int64_t, const LineSegment*> old_by_id;
  for (const LineSegment& segment : old) old_by_id.emplace(segment.id, &segment);
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    if (ids[i] == 0) {
      fresh[i].id = next_id_++;
      delta.added.push_back(fresh[i]);
      continue;
    }
    fresh[i].id = ids[i];
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
