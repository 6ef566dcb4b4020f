#pragma once
// A digest of a line map that two processes can compare without exchanging the map: FNV-1a
// (64 bit) over each segment's id and millimetre endpoints, in id order. Equal digests mean the
// same segments at LineMap's own quantum (line_map::kCoordinateQuantumM), whatever carried them.

#include <cstdint>
#include <string>
#include <vector>

#include "pena/io/line_csv.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::services {

// The digest of segments sorted by id (LineMap::segments() order).
std::uint64_t MapDigest(const std::vector<line_map::LineSegment>& segments);
// The same digest of rows read from a line CSV (e.g. pena-fusion's global_map.csv).
std::uint64_t MapDigest(const std::vector<io::LineRow>& rows);
// The digest as 16 lower-case hex digits.
std::string DigestHex(std::uint64_t digest);

}  // namespace pena::services
