#include "map_digest.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

#include "pena/line_map/map_delta.hpp"

namespace pena::services {
namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ULL;
constexpr std::uint64_t kFnvPrime = 1099511628211ULL;

void Mix(std::uint64_t& hash, std::int64_t value) {
  auto bits = static_cast<std::uint64_t>(value);
  for (int byte = 0; byte < 8; ++byte) {
    hash ^= (bits & 0xffU);
    hash *= kFnvPrime;
    bits >>= 8;
  }
}

// One segment: id and endpoints in whole millimetres (the quantum every LineMap stores, so a
// CSV written with millimetre precision gives the same numbers).
void MixSegment(std::uint64_t& hash, std::int64_t id, const geometry::Segment2& segment) {
  const double quantum = line_map::kCoordinateQuantumM;
  const std::array<double, 4> coords{segment.start_m.x(), segment.start_m.y(), segment.end_m.x(),
                                     segment.end_m.y()};
  Mix(hash, id);
  for (const double value : coords) Mix(hash, line_map::ToQuanta(value, quantum));
}

}  // namespace

std::uint64_t MapDigest(const std::vector<line_map::LineSegment>& segments) {
  std::uint64_t hash = kFnvOffset;
  for (const line_map::LineSegment& line : segments) MixSegment(hash, line.id, line.segment);
  return hash;
}

std::uint64_t MapDigest(const std::vector<io::LineRow>& rows) {
  std::vector<const io::LineRow*> sorted;
  for (const io::LineRow& row : rows) sorted.push_back(&row);
  std::sort(sorted.begin(), sorted.end(),
            [](const io::LineRow* a, const io::LineRow* b) { return a->id < b->id; });
  std::uint64_t hash = kFnvOffset;
  for (const io::LineRow* row : sorted) MixSegment(hash, row->id, row->segment);
  return hash;
}

std::string DigestHex(std::uint64_t digest) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(digest));
  return text;
}

}  // namespace pena::services
