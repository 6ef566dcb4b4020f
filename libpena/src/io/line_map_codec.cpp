#include "pena/io/line_map_codec.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "line_map.pb.h"
#include "pena/io/input_error.hpp"

namespace pena::io {
namespace {

namespace wire = pena::line_map_wire;
using line_map::kCoordinateQuantumM;
using line_map::kRmsQuantumM;
using line_map::LineSegment;

// Counts travel as integers; doubles hold every integer up to 2^53 exactly.
constexpr double kMaxExactCount = 9007199254740992.0;
constexpr std::int64_t kMaxCoordinateMm = 2'000'000'000;  // kMaxCoordinateM in millimetres

// A field the bytes cannot stand for; Decode* turn it into an InputError.
class WireError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string Where(const LineSegment& segment) {
  return "segment " + std::to_string(segment.id) + ": ";
}

// Whole quanta of `value_m`, or invalid_argument if that would not decode to the same double.
std::int64_t ExactQuanta(double value_m, double quantum_m, const LineSegment& segment,
                         const char* field) {
  const std::string what = Where(segment) + field + " = " + std::to_string(value_m);
  if (!std::isfinite(value_m) || std::abs(value_m) > line_map::kMaxCoordinateM) {
    throw std::invalid_argument(what + " is not finite or out of range");
  }
  const std::int64_t quanta = line_map::ToQuanta(value_m, quantum_m);
  if (line_map::FromQuanta(quanta, quantum_m) != value_m) {
    throw std::invalid_argument(what + " is not a whole number of quanta (only LineMap output is)");
  }
  return quanta;
}

std::uint64_t ExactCount(double count, const LineSegment& segment, const char* field) {
  if (!(count >= 0.0 && count <= kMaxExactCount && std::floor(count) == count)) {
    throw std::invalid_argument(Where(segment) + field + " = " + std::to_string(count) +
                                " is not a whole count");
  }
  return static_cast<std::uint64_t>(count);
}

void ToWire(const LineSegment& segment, wire::LineSegmentMsg* out) {
  if (segment.id <= 0) throw std::invalid_argument(Where(segment) + "id must be > 0");
  const auto& [start, end] = segment.segment;
  const std::int64_t x = ExactQuanta(start.x(), kCoordinateQuantumM, segment, "start_m.x");
  const std::int64_t y = ExactQuanta(start.y(), kCoordinateQuantumM, segment, "start_m.y");
  out->set_id(segment.id);
  out->set_start_x_mm(x);
  out->set_start_y_mm(y);
  out->set_end_dx_mm(ExactQuanta(end.x(), kCoordinateQuantumM, segment, "end_m.x") - x);
  out->set_end_dy_mm(ExactQuanta(end.y(), kCoordinateQuantumM, segment, "end_m.y") - y);
  out->set_support_cells(ExactCount(segment.support_cells, segment, "support_cells"));
  out->set_observations(ExactCount(segment.observations, segment, "observations"));
  const std::int64_t rms = ExactQuanta(segment.rms_error_m, kRmsQuantumM, segment, "rms_error_m");
  if (rms < 0 || rms > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument(Where(segment) + "rms_error_m must be in [0, 429496] m");
  }
  out->set_rms_error_100um(static_cast<std::uint32_t>(rms));
  for (const std::string& entry : segment.provenance) out->add_provenance(entry);
  const std::int64_t sd = ExactQuanta(segment.error_sd_m, line_map::kErrorSdQuantumM, segment,
                                      "error_sd_m");
  if (sd < 0 || segment.error_sd_m > line_map::kMaxErrorSdM) {
    throw std::invalid_argument(Where(segment) + "error_sd_m must be in [0, 655.35] m");
  }
  out->set_seen_by_entities(segment.seen_by_entities);
  out->set_error_sd_cm(static_cast<std::uint32_t>(sd));
}

double Coordinate(std::int64_t mm, const std::string& where, const char* field) {
  if (mm < -kMaxCoordinateMm || mm > kMaxCoordinateMm) {
    throw WireError(where + field + " = " + std::to_string(mm) + " mm is out of range");
  }
  return line_map::FromQuanta(mm, kCoordinateQuantumM);
}

double Count(std::uint64_t count, const std::string& where, const char* field) {
  if (static_cast<double>(count) > kMaxExactCount) {
    throw WireError(where + field + " = " + std::to_string(count) + " exceeds 2^53");
  }
  return static_cast<double>(count);
}

// Checked before adding to a start coordinate, so the sum cannot overflow int64.
std::int64_t Difference(std::int64_t mm, const std::string& where, const char* field) {
  if (mm < -2 * kMaxCoordinateMm || mm > 2 * kMaxCoordinateMm) {
    throw WireError(where + field + " = " + std::to_string(mm) + " mm is out of range");
  }
  return mm;
}

LineSegment FromWire(const wire::LineSegmentMsg& msg, const std::string& where) {
  if (msg.id() <= 0) throw WireError(where + "id must be > 0, got " + std::to_string(msg.id()));
  LineSegment segment;
  segment.id = msg.id();
  const double x_m = Coordinate(msg.start_x_mm(), where, "start_x_mm");
  const double y_m = Coordinate(msg.start_y_mm(), where, "start_y_mm");
  const std::int64_t end_x_mm = msg.start_x_mm() + Difference(msg.end_dx_mm(), where, "end_dx_mm");
  const std::int64_t end_y_mm = msg.start_y_mm() + Difference(msg.end_dy_mm(), where, "end_dy_mm");
  segment.segment.start_m = {x_m, y_m};
  segment.segment.end_m = {Coordinate(end_x_mm, where, "start_x_mm + end_dx_mm"),
                           Coordinate(end_y_mm, where, "start_y_mm + end_dy_mm")};
  segment.support_cells = Count(msg.support_cells(), where, "support_cells");
  segment.observations = Count(msg.observations(), where, "observations");
  segment.rms_error_m = line_map::FromQuanta(msg.rms_error_100um(), kRmsQuantumM);
  segment.provenance.assign(msg.provenance().begin(), msg.provenance().end());
  segment.seen_by_entities = msg.seen_by_entities();
  if (msg.error_sd_cm() > line_map::ToQuanta(line_map::kMaxErrorSdM, line_map::kErrorSdQuantumM)) {
    throw WireError(where + "error_sd_cm = " + std::to_string(msg.error_sd_cm()) +
                    " is beyond 65535");
  }
  segment.error_sd_m = line_map::FromQuanta(msg.error_sd_cm(), line_map::kErrorSdQuantumM);
  return segment;
}

void CheckSchema(std::uint32_t schema_version) {
  if (schema_version != kLineMapSchemaVersion) {
    throw WireError("schema_version " + std::to_string(schema_version) + " is not " +
                    std::to_string(kLineMapSchemaVersion) +
                    (schema_version == 0 ? " (absent: not a line map message?)" : ""));
  }
}

template <class Message>
Message Parse(std::string_view bytes) {
  Message msg;
  if (!msg.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    throw WireError("not a valid " + msg.GetTypeName() + " (" + std::to_string(bytes.size()) +
                    " bytes)");
  }
  CheckSchema(msg.schema_version());
  return msg;
}

std::string Serialise(const google::protobuf::MessageLite& msg) {
  std::string bytes;
  if (!msg.SerializeToString(&bytes)) throw std::invalid_argument("line map message too large");
  return bytes;
}

}  // namespace

std::string EncodeDelta(const line_map::MapDelta& delta) {
  wire::MapDeltaMsg msg;
  msg.set_schema_version(kLineMapSchemaVersion);
  msg.set_from_version(delta.from_version);
  msg.set_to_version(delta.to_version);
  for (const LineSegment& segment : delta.added) ToWire(segment, msg.add_added());
  for (const LineSegment& segment : delta.changed) ToWire(segment, msg.add_changed());
  for (const std::int64_t id : delta.removed) msg.add_removed(id);
  return Serialise(msg);
}

line_map::MapDelta DecodeDelta(std::string_view bytes, const std::string& name) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(name, 0, "too large for a line map delta");
  }
  try {
    const auto msg = Parse<wire::MapDeltaMsg>(bytes);
    line_map::MapDelta delta;
    delta.from_version = msg.from_version();
    delta.to_version = msg.to_version();
    for (int i = 0; i < msg.added_size(); ++i) {
      delta.added.push_back(FromWire(msg.added(i), "added[" + std::to_string(i) + "]: "));
    }
    for (int i = 0; i < msg.changed_size(); ++i) {
      delta.changed.push_back(FromWire(msg.changed(i), "changed[" + std::to_string(i) + "]: "));
    }
    delta.removed.assign(msg.removed().begin(), msg.removed().end());
    return delta;
  } catch (const WireError& error) {
    throw InputError(name, 0, error.what());
  }
}

std::string EncodeSnapshot(const line_map::MapSnapshot& snapshot) {
  wire::MapSnapshotMsg msg;
  msg.set_schema_version(kLineMapSchemaVersion);
  msg.set_version(snapshot.version);
  msg.set_next_id(snapshot.next_id);
  for (const LineSegment& segment : snapshot.segments) ToWire(segment, msg.add_segments());
  return Serialise(msg);
}

line_map::MapSnapshot DecodeSnapshot(std::string_view bytes, const std::string& name) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(name, 0, "too large for a line map snapshot");
  }
  try {
    const auto msg = Parse<wire::MapSnapshotMsg>(bytes);
    line_map::MapSnapshot snapshot;
    snapshot.version = msg.version();
    snapshot.next_id = msg.next_id();
    for (int i = 0; i < msg.segments_size(); ++i) {
      snapshot.segments.push_back(
          FromWire(msg.segments(i), "segments[" + std::to_string(i) + "]: "));
    }
    return snapshot;
  } catch (const WireError& error) {
    throw InputError(name, 0, error.what());
  }
}

}  // namespace pena::io
