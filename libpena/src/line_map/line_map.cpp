#include "pena/line_map/line_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "merge_geometry.hpp"

namespace pena::line_map {
namespace {

std::string Text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void Require(bool ok, const std::string& what, double value) {
  if (!ok) throw std::invalid_argument(what + ", got " + Text(value));
}

void ValidateOptions(const LineMapOptions& options) {
  Require(std::isfinite(options.merge_distance_m) && options.merge_distance_m > 0.0,
          "line_map.merge_distance_m must be > 0 (metres)", options.merge_distance_m);
  Require(std::isfinite(options.merge_angle_rad) && options.merge_angle_rad > 0.0 &&
              options.merge_angle_rad < std::numbers::pi / 2.0,
          "line_map.merge_angle_rad must be in (0, pi/2) (radians)", options.merge_angle_rad);
  Require(std::isfinite(options.max_gap_m) && options.max_gap_m >= 0.0,
          "line_map.max_gap_m must be >= 0 (metres)", options.max_gap_m);
  Require(std::isfinite(options.refit_band_m) && options.refit_band_m >= 0.0,
          "line_map.refit_band_m must be >= 0 (metres)", options.refit_band_m);
  Require(std::isfinite(options.absorb_distance_m) && options.absorb_distance_m >= 0.0,
          "line_map.absorb_distance_m must be >= 0 (metres)", options.absorb_distance_m);
}

// Checks one fresh segment before anything changes, so a bad batch leaves the map untouched.
void ValidateFresh(const LineSegment& segment, std::size_t index) {
  const std::string name = "fresh[" + std::to_string(index) + "].";
  for (const auto& [field, point] : {std::pair{"segment.start_m", segment.segment.start_m},
                                     std::pair{"segment.end_m", segment.segment.end_m}}) {
    for (const double coordinate : {point.x(), point.y()}) {
      Require(std::isfinite(coordinate) && std::abs(coordinate) <= kMaxCoordinateM,
              name + field + " must be finite and within " + Text(kMaxCoordinateM) + " m",
              coordinate);
    }
  }
  Require(std::isfinite(segment.support_cells) && segment.support_cells >= 0.0,
          name + "support_cells must be >= 0 (cells)", segment.support_cells);
  Require(std::isfinite(segment.observations) && segment.observations >= 0.0,
          name + "observations must be >= 0 (hits)", segment.observations);
  Require(std::isfinite(segment.rms_error_m) && segment.rms_error_m >= 0.0,
          name + "rms_error_m must be >= 0 (metres)", segment.rms_error_m);
}

void AppendUnique(std::vector<std::string>& list, const std::string& entry) {
  if (!entry.empty() && std::find(list.begin(), list.end(), entry) == list.end()) {
    list.push_back(entry);
  }
}

bool Contains(const std::vector<std::int64_t>& ids, std::int64_t id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

}  // namespace

LineMap::LineMap(LineMapOptions options) : options_(options) { ValidateOptions(options_); }

LineMap LineMap::FromSnapshot(const MapSnapshot& snapshot, LineMapOptions options) {
  LineMap map(options);
  for (const LineSegment& segment : snapshot.segments) {
    if (segment.id <= 0) {
      throw std::invalid_argument("snapshot segment id must be > 0, got " +
                                  std::to_string(segment.id));
    }
    if (!map.segments_.emplace(segment.id, segment).second) {
      throw std::invalid_argument("snapshot holds segment id " + std::to_string(segment.id) +
                                  " twice");
    }
  }
  const std::int64_t max_id = map.segments_.empty() ? 0 : map.segments_.rbegin()->first;
  if (snapshot.next_id <= max_id) {
    throw std::invalid_argument("snapshot next_id must be > largest id " +
                                std::to_string(max_id) + ", got " +
                                std::to_string(snapshot.next_id));
  }
  map.version_ = snapshot.version;
  map.next_id_ = snapshot.next_id;
  return map;
}

MapDelta LineMap::Integrate(const std::vector<LineSegment>& fresh, const std::string& source) {
  for (std::size_t i = 0; i < fresh.size(); ++i) ValidateFresh(fresh[i], i);
  for (const LineSegment& segment : fresh) {
    // Quantised before merging so that what the map stores is exactly what the wire carries.
    LineSegment quantised = QuantiseSegment(segment);
    if (quantised.segment.start_m == quantised.segment.end_m) continue;
    quantised.id = 0;
    quantised.provenance.clear();
    for (const std::string& entry : segment.provenance) AppendUnique(quantised.provenance, entry);
    AppendUnique(quantised.provenance, source);
    IntegrateOne(std::move(quantised));
  }
  return CollectDelta();
}

void LineMap::IntegrateOne(LineSegment fresh) {
  // Absorb matching walls until none is left: a refit that grew may reach the next piece
  // (A absorbs B, then the longer A reaches C). Each round refits from the original parts.
  // With a refit band, a fresh piece off the stored line only extends it (bounded drift), and
  // one a little farther than merge_distance_m is absorbed that way instead of becoming a
  // parallel duplicate.
  const bool bounded = options_.refit_band_m > 0.0;
  const double first_distance_m =
      bounded ? std::max(options_.merge_distance_m, options_.absorb_distance_m)
              : options_.merge_distance_m;
  std::vector<std::int64_t> members;
  LineSegment merged = fresh;
  for (auto matches = FindMatches(merged, members, first_distance_m); !matches.empty();
       matches = FindMatches(merged, members, options_.merge_distance_m)) {
    members.insert(members.end(), matches.begin(), matches.end());
    std::sort(members.begin(), members.end());
    std::vector<const LineSegment*> parts;
    for (const std::int64_t id : members) parts.push_back(&segments_.at(id));
    if (bounded &&
        !detail::WithinBand(fresh.segment, detail::Refit(parts).segment, options_.refit_band_m)) {
      // The side with more evidence keeps its line; the other only widens the span.
      double stored_weight = 0.0;
      for (const LineSegment* part : parts) stored_weight += detail::Weight(*part);
      merged = QuantiseSegment(
          stored_weight >= detail::Weight(fresh)
              ? detail::Refit(parts, {&fresh})
              : detail::OrientLike(detail::Refit({&fresh}, parts), parts.front()->segment));
      continue;
    }
    parts.push_back(&fresh);
    merged = QuantiseSegment(detail::Refit(parts));
  }
  if (members.empty()) {
    merged.id = next_id_++;
    Touch(merged.id);
    segments_.emplace(merged.id, std::move(merged));
    return;
  }
  // The oldest id survives; provenance keeps its history, then each absorbed id and its history.
  const std::int64_t survivor = members.front();
  merged.id = survivor;
  merged.provenance = segments_.at(survivor).provenance;
  for (std::size_t i = 1; i < members.size(); ++i) {
    AppendUnique(merged.provenance, "#" + std::to_string(members[i]));
    for (const std::string& entry : segments_.at(members[i]).provenance) {
      AppendUnique(merged.provenance, entry);
    }
  }
  for (const std::string& entry : fresh.provenance) AppendUnique(merged.provenance, entry);
  for (const std::int64_t id : members) Touch(id);
  for (std::size_t i = 1; i < members.size(); ++i) segments_.erase(members[i]);
  segments_[survivor] = std::move(merged);
}

std::vector<std::int64_t> LineMap::FindMatches(const LineSegment& segment,
                                               const std::vector<std::int64_t>& exclude,
                                               double distance_m) const {
  // A linear scan: maps of a building hold hundreds of segments; a spatial index can come later.
  LineMapOptions options = options_;
  options.merge_distance_m = distance_m;
  std::vector<std::int64_t> matches;
  for (const auto& [id, stored] : segments_) {
    if (!Contains(exclude, id) && detail::SameWall(segment.segment, stored.segment, options)) {
      matches.push_back(id);
    }
  }
  return matches;
}

void LineMap::Touch(std::int64_t id) {
  if (before_.contains(id)) return;
  const auto it = segments_.find(id);
  before_.emplace(id, it == segments_.end() ? std::nullopt : std::optional(it->second));
}

MapDelta LineMap::CollectDelta() {
  MapDelta delta;
  delta.from_version = version_;
  for (const auto& [id, old] : before_) {
    const auto now = segments_.find(id);
    if (!old && now != segments_.end()) {
      delta.added.push_back(now->second);
    } else if (old && now == segments_.end()) {
      delta.removed.push_back(id);
    } else if (old && !SameSegment(*old, now->second)) {
      delta.changed.push_back(now->second);
    }  // else: added and absorbed within this call, nobody saw it
  }
  before_.clear();
  if (!delta.empty()) ++version_;
  delta.to_version = version_;
  return delta;
}

ApplyResult LineMap::Apply(const MapDelta& delta) {
  const std::string versions =
      "delta " + std::to_string(delta.from_version) + "->" + std::to_string(delta.to_version);
  if (delta.to_version != delta.from_version + (delta.empty() ? 0 : 1)) {
    return {ApplyStatus::kInvalid, versions + ": a non-empty delta must advance the version by 1"};
  }
  if (delta.empty() && delta.from_version == version_) return {};
  if (delta.to_version <= version_) {
    return {ApplyStatus::kStale, versions + " is already in map version " +
                                     std::to_string(version_)};
  }
  if (delta.from_version != version_) {
    return {ApplyStatus::kVersionGap, versions + " does not follow map version " +
                                          std::to_string(version_) + ": a delta was lost"};
  }
  if (std::string problem = CheckIds(delta); !problem.empty()) {
    return {ApplyStatus::kInvalid, versions + ": " + problem};
  }
  for (const std::int64_t id : delta.removed) segments_.erase(id);
  for (const LineSegment& segment : delta.changed) segments_[segment.id] = segment;
  for (const LineSegment& segment : delta.added) {
    segments_.emplace(segment.id, segment);
    next_id_ = std::max(next_id_, segment.id + 1);
  }
  version_ = delta.to_version;
  return {};
}

std::string LineMap::CheckIds(const MapDelta& delta) const {
  std::set<std::int64_t> seen;
  const auto once = [&seen](std::int64_t id) { return seen.insert(id).second; };
  for (const LineSegment& segment : delta.added) {
    const std::string id = std::to_string(segment.id);
    if (segment.id <= 0) return "added id " + id + " is not > 0";
    if (segments_.contains(segment.id)) return "added id " + id + " is already in the map";
    if (!once(segment.id)) return "id " + id + " appears twice";
  }
  for (const LineSegment& segment : delta.changed) {
    const std::string id = std::to_string(segment.id);
    if (!segments_.contains(segment.id)) return "changed id " + id + " is not in the map";
    if (!once(segment.id)) return "id " + id + " appears twice";
  }
  for (const std::int64_t id : delta.removed) {
    if (!segments_.contains(id)) return "removed id " + std::to_string(id) + " is not in the map";
    if (!once(id)) return "id " + std::to_string(id) + " appears twice";
  }
  return {};
}

MapSnapshot LineMap::Snapshot() const { return {version_, next_id_, segments()}; }

std::vector<LineSegment> LineMap::segments() const {
  std::vector<LineSegment> all;
  all.reserve(segments_.size());
  for (const auto& entry : segments_) all.push_back(entry.second);
  return all;
}

}  // namespace pena::line_map
