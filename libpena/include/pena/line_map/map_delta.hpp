#pragma once
// Versioned changes of a line map: what a sender publishes and a receiver applies.
// Values are quantised (endpoints to 1 mm, fit error to 0.1 mm, counts to integers) when a LineMap
// stores them, so the wire encoding carries them exactly and a receiver gets the same doubles.

#include <cstdint>
#include <string>
#include <vector>

#include "pena/line_map/line_segment.hpp"

namespace pena::line_map {

// Endpoint resolution in metres (1 mm); map coordinates are integer multiples of it.
inline constexpr double kCoordinateQuantumM = 0.001;
// Fit error resolution in metres (0.1 mm).
inline constexpr double kRmsQuantumM = 0.0001;
// Resolution of a global wall's estimated error sd in metres (1 cm: enough to draw confidence,
// coarse enough that the estimate's drift between rebuilds rarely re-sends a wall).
inline constexpr double kErrorSdQuantumM = 0.01;
// Largest estimated error sd a quantised wall carries, metres (fits 16 bits of centimetres).
inline constexpr double kMaxErrorSdM = 655.35;
// Largest coordinate magnitude in metres a quantised map holds (fits sint32 millimetres).
inline constexpr double kMaxCoordinateM = 2.0e6;

// The change from map version from_version to to_version (= from_version + 1; equal if empty).
struct MapDelta {
  std::uint64_t from_version = 0;
  std::uint64_t to_version = 0;
  std::vector<LineSegment> added;     // new ids, sorted by id
  std::vector<LineSegment> changed;   // existing ids, full new value, sorted by id
  std::vector<std::int64_t> removed;  // ids absorbed by a merge, sorted
  bool empty() const { return added.empty() && changed.empty() && removed.empty(); }
};

// A whole map at one version: enough to rebuild it (and to resume integrating on it).
struct MapSnapshot {
  std::uint64_t version = 0;
  std::int64_t next_id = 1;           // the id the next new segment gets
  std::vector<LineSegment> segments;  // sorted by id
};

// `value_m` as a whole number of quanta (e.g. millimetres for kCoordinateQuantumM).
std::int64_t ToQuanta(double value_m, double quantum_m);
// Metres from a whole number of quanta; FromQuanta(ToQuanta(x)) is what every LineMap stores.
double FromQuanta(std::int64_t quanta, double quantum_m);
// `value_m` rounded to the nearest multiple of `quantum_m` (the same double on every machine).
double Quantise(double value_m, double quantum_m);
// The segment with endpoints, fit error, counts and error sd quantised (see the file comment;
// the error sd is clamped to kMaxErrorSdM).
LineSegment QuantiseSegment(LineSegment segment);
// True if every field, provenance included, is identical (doubles compared bit for bit).
bool SameSegment(const LineSegment& a, const LineSegment& b);
// True if both snapshots hold the same version and identical segments (next_id ignored).
bool SameMap(const MapSnapshot& a, const MapSnapshot& b);

}  // namespace pena::line_map
