#pragma once
// A line map that merges what it is given: segments seen again, collinear pieces and
// revisits of the same wall become one segment with a stable id, so the map does not grow with
// revisits; each change is a versioned MapDelta that a receiver applies to get the same map.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pena/line_map/line_segment.hpp"
#include "pena/line_map/map_delta.hpp"

namespace pena::line_map {

// When two segments are the same wall (docs/line-map.md). Validated by LineMap's constructor.
struct LineMapOptions {
  double merge_distance_m = 0.10;       // endpoints of the shorter within this of the longer's line
  double merge_angle_rad = 0.17453292519943295;  // 10 deg: directions (mod pi) at most this apart
  double max_gap_m = 0.30;              // along the line: overlapping or at most this far apart
  // Bounded drift (docs/line-map.md): a fresh segment moves a matched wall's line only if both its
  // ends lie within this of it, else only extends its span. 0 = off.
  double refit_band_m = 0.0;
  // With refit_band_m > 0: a near duplicate within this is absorbed (span only) by the wall it
  // copies; <= merge_distance_m = off. Keep it below the spacing of parallel walls.
  double absorb_distance_m = 0.0;
};

// Why Apply refused a delta (the map is then unchanged).
enum class ApplyStatus {
  kApplied,      // the map is now at delta.to_version
  kStale,        // delta.to_version <= version(): already contained (e.g. after a snapshot)
  kVersionGap,   // delta.from_version > version(): a delta was lost; ask for a snapshot
  kInvalid,      // inconsistent delta: bad versions, unknown id changed/removed, id added twice
};

// The outcome of Apply: status plus a message naming versions or the offending id.
struct ApplyResult {
  ApplyStatus status = ApplyStatus::kApplied;
  std::string message;
  bool ok() const { return status == ApplyStatus::kApplied; }
};

// The map of one sender (Integrate) or receiver (Apply), world frame, metres.
class LineMap {
 public:
  // Throws std::invalid_argument naming the field and unit for a bad option.
  explicit LineMap(LineMapOptions options = {});
  // Rebuilds a map from a snapshot; throws std::invalid_argument for duplicate or non-positive ids.
  static LineMap FromSnapshot(const MapSnapshot& snapshot, LineMapOptions options = {});

  // Adds freshly extracted segments from `source` (entity or submap id, kept in provenance),
  // merging each into the walls it matches; their ids are ignored. Returns the change (empty if
  // none, then the version stays). Throws std::invalid_argument for non-finite or negative values.
  MapDelta Integrate(const std::vector<LineSegment>& fresh, const std::string& source);
  // Applies a sender's delta if it follows version(); otherwise leaves the map as it was.
  ApplyResult Apply(const MapDelta& delta);

  // The whole map at version() (segments sorted by id).
  MapSnapshot Snapshot() const;
  // Number of changes so far (0 = empty map never changed).
  std::uint64_t version() const { return version_; }
  // All segments, sorted by id.
  std::vector<LineSegment> segments() const;
  // Number of segments.
  std::size_t size() const { return segments_.size(); }
  // True if a segment with this id is in the map.
  bool HasSegment(std::int64_t id) const { return segments_.contains(id); }
  // The options in use.
  const LineMapOptions& options() const { return options_; }

 private:
  // Merges one quantised fresh segment into the map, recording touched ids' old values.
  void IntegrateOne(LineSegment fresh);
  // Ids of stored segments (not in `exclude`) that are the same wall as `segment`.
  std::vector<std::int64_t> FindMatches(const LineSegment& segment,
                                        const std::vector<std::int64_t>& exclude,
                                        double distance_m) const;
  // Empty if the ids of `delta` fit this map (added new, changed and removed known, none twice).
  std::string CheckIds(const MapDelta& delta) const;
  // Remembers the value of `id` before this Integrate call first touches it.
  void Touch(std::int64_t id);
  // The delta from the remembered old values to the current map; clears them.
  MapDelta CollectDelta();

  LineMapOptions options_;
  std::uint64_t version_ = 0;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, LineSegment> segments_;
  std::map<std::int64_t, std::optional<LineSegment>> before_;  // during Integrate only
};

}  // namespace pena::line_map
