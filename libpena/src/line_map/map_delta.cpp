#include "pena/line_map/map_delta.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace pena::line_map {
namespace {

// Division by a whole number of quanta per metre (1000, 10000) is exact IEEE arithmetic, so the
// sender and every receiver get the same double; multiplying by 0.001 could differ in the last bit.
double QuantaPerMetre(double quantum_m) { return std::round(1.0 / quantum_m); }

bool SameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool SameBits(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return SameBits(a.x(), b.x()) && SameBits(a.y(), b.y());
}

}  // namespace

std::int64_t ToQuanta(double value_m, double quantum_m) {
  return std::llround(value_m * QuantaPerMetre(quantum_m));
}

double FromQuanta(std::int64_t quanta, double quantum_m) {
  return static_cast<double>(quanta) / QuantaPerMetre(quantum_m);
}

double Quantise(double value_m, double quantum_m) {
  return FromQuanta(ToQuanta(value_m, quantum_m), quantum_m);
}

LineSegment QuantiseSegment(LineSegment segment) {
  for (Eigen::Vector2d* point : {&segment.segment.start_m, &segment.segment.end_m}) {
    point->x() = Quantise(point->x(), kCoordinateQuantumM);
    point->y() = Quantise(point->y(), kCoordinateQuantumM);
  }
  segment.rms_error_m = Quantise(segment.rms_error_m, kRmsQuantumM);
  // Counts are sums of whole cells and hits; rounding keeps them whole after weighted merges.
  segment.support_cells = std::round(segment.support_cells);
  segment.observations = std::round(segment.observations);
  // NaN and negative estimates are no estimate (0).
  const double sd_m = segment.error_sd_m > 0.0 ? std::min(segment.error_sd_m, kMaxErrorSdM) : 0.0;
  segment.error_sd_m = Quantise(sd_m, kErrorSdQuantumM);
  return segment;
}

bool SameSegment(const LineSegment& a, const LineSegment& b) {
  return a.id == b.id && SameBits(a.segment.start_m, b.segment.start_m) &&
         SameBits(a.segment.end_m, b.segment.end_m) &&
         SameBits(a.support_cells, b.support_cells) &&
         SameBits(a.observations, b.observations) && SameBits(a.rms_error_m, b.rms_error_m) &&
         a.provenance == b.provenance && a.seen_by_entities == b.seen_by_entities &&
         SameBits(a.error_sd_m, b.error_sd_m);
}

bool SameMap(const MapSnapshot& a, const MapSnapshot& b) {
  if (a.version != b.version || a.segments.size() != b.segments.size()) return false;
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    if (!SameSegment(a.segments[i], b.segments[i])) return false;
  }
  return true;
}

}  // namespace pena::line_map
