#pragma once
// The compact encoding of line-map deltas and snapshots for the radio link (docs/gateway.md,
// "Map deltas"): the gateway sends it, `pena map` reports its size. Endpoints in whole
// millimetres, each segment's id and start delta-coded against the previous segment, its end
// against its own start, all as adaptive Rice codes on a bit stream; provenance strings once per
// message in a table, and one bit when a segment's list repeats the previous one's; a global
// wall's support (entities that saw it, error sd in cm) only in a message that has some. Exact for
// what a LineMap produces, so the far side's map equals the near side's.

#include <optional>
#include <string>
#include <string_view>

#include "pena/line_map/map_delta.hpp"

namespace pena::line_map {

// Packs the changed segments of a delta (versions travel in MapUpdate). Throws
// std::invalid_argument for a value not on the map's quanta (only LineMap output is exact) and
// for removed ids that do not increase (MapDelta keeps them sorted).
std::string PackDelta(const MapDelta& delta);
// Unpacks PackDelta bytes into `delta` (versions set by the caller); nullopt and `error` set
// (with the byte offset) for malformed bytes.
std::optional<MapDelta> UnpackDelta(std::string_view bytes, std::string* error);

// Packs next_id and the segments of a snapshot; throws like PackDelta.
std::string PackSnapshot(const MapSnapshot& snapshot);
// Unpacks PackSnapshot bytes (version set by the caller); nullopt and `error` for bad bytes.
std::optional<MapSnapshot> UnpackSnapshot(std::string_view bytes, std::string* error);

}  // namespace pena::line_map
