#include "pena/gateway/map_packing.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "pena/gateway/varint.hpp"

namespace pena::gateway {
namespace {

using line_map::LineSegment;

// Largest coordinate in quanta a packed segment may carry (line_map::kMaxCoordinateM in mm).
constexpr std::int64_t kMaxCoordinateQuanta = 2'000'000'000;
// Smallest packed segment: id, 4 coordinates, 3 counts, provenance count (one byte each).
constexpr std::size_t kMinSegmentBytes = 9;

// The quanta of `value_m`, throwing if it is not an exact multiple (what LineMap stores).
std::int64_t ExactQuanta(double value_m, double quantum_m, const char* what) {
  const std::int64_t quanta = line_map::ToQuanta(value_m, quantum_m);
  if (line_map::FromQuanta(quanta, quantum_m) != value_m) {
    throw std::invalid_argument(std::string("map packing: ") + what + " " +
                                std::to_string(value_m) + " is not on the map's quanta");
  }
  return quanta;
}

std::uint64_t ExactCount(double count, const char* what) {
  if (!(count >= 0.0) || count != std::floor(count) || count > 1e15) {
    throw std::invalid_argument(std::string("map packing: ") + what + " " + std::to_string(count) +
                                " is not a whole non-negative count");
  }
  return static_cast<std::uint64_t>(count);
}

// Packs segments with ids and starts relative to the previous one; provenance as table indices.
class SegmentPacker {
 public:
  void Collect(const std::vector<LineSegment>& segments) {
    for (const LineSegment& segment : segments) {
      for (const std::string& source : segment.provenance) table_.emplace(source, table_.size());
    }
  }
  void PutTable(ByteWriter& out) const {
    std::vector<const std::string*> ordered(table_.size());
    for (const auto& [text, index] : table_) ordered[index] = &text;
    out.PutVarint(ordered.size());
    for (const std::string* text : ordered) out.PutString(*text);
  }
  void Put(ByteWriter& out, const std::vector<LineSegment>& segments) {
    out.PutVarint(segments.size());
    for (const LineSegment& segment : segments) PutOne(out, segment);
  }

 private:
  void PutOne(ByteWriter& out, const LineSegment& s) {
    const double q = line_map::kCoordinateQuantumM;
    const std::int64_t sx = ExactQuanta(s.segment.start_m.x(), q, "start x");
    const std::int64_t sy = ExactQuanta(s.segment.start_m.y(), q, "start y");
    if (s.id <= 0) throw std::invalid_argument("map packing: segment id must be > 0");
    out.PutSigned(s.id - previous_id_);
    out.PutSigned(sx - previous_x_);
    out.PutSigned(sy - previous_y_);
    out.PutSigned(ExactQuanta(s.segment.end_m.x(), q, "end x") - sx);
    out.PutSigned(ExactQuanta(s.segment.end_m.y(), q, "end y") - sy);
    out.PutVarint(ExactCount(s.support_cells, "support_cells"));
    out.PutVarint(ExactCount(s.observations, "observations"));
    const std::int64_t rms = ExactQuanta(s.rms_error_m, line_map::kRmsQuantumM, "rms error");
    if (rms < 0) throw std::invalid_argument("map packing: rms error must be >= 0");
    out.PutVarint(static_cast<std::uint64_t>(rms));
    out.PutVarint(s.provenance.size());
    for (const std::string& source : s.provenance) out.PutVarint(table_.at(source));
    previous_id_ = s.id;
    previous_x_ = sx;
    previous_y_ = sy;
  }

  std::map<std::string, std::size_t> table_;
  std::int64_t previous_id_ = 0;
  std::int64_t previous_x_ = 0;
  std::int64_t previous_y_ = 0;
};

// The inverse of SegmentPacker; every value is range-checked so no input overflows.
class SegmentUnpacker {
 public:
  explicit SegmentUnpacker(ByteReader& in) : in_(in) {}
  void GetTable() {
    const std::uint64_t count = in_.GetCount(1);
    for (std::uint64_t i = 0; i < count && !in_.failed(); ++i) table_.push_back(in_.GetString());
  }
  std::vector<LineSegment> Get() {
    const std::uint64_t count = in_.GetCount(kMinSegmentBytes);
    std::vector<LineSegment> segments;
    segments.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count && !in_.failed(); ++i) segments.push_back(GetOne());
    return segments;
  }

 private:
  std::int64_t Step(std::int64_t previous, const char* what) {
    const std::int64_t delta = in_.GetSigned();
    if (delta > 2 * kMaxCoordinateQuanta || delta < -2 * kMaxCoordinateQuanta) {
      in_.Fail(std::string(what) + " step out of range");
      return 0;
    }
    const std::int64_t value = previous + delta;
    if (value > kMaxCoordinateQuanta || value < -kMaxCoordinateQuanta) {
      in_.Fail(std::string(what) + " out of range");
      return 0;
    }
    return value;
  }
  double Count(const char* what) {
    const std::uint64_t value = in_.GetVarint();
    if (value > (1ULL << 50)) in_.Fail(std::string(what) + " out of range");
    return static_cast<double>(value);
  }
  LineSegment GetOne() {
    const double q = line_map::kCoordinateQuantumM;
    LineSegment s;
    previous_id_ = Step(previous_id_, "id");
    s.id = previous_id_;
    if (s.id <= 0 && !in_.failed()) in_.Fail("segment id " + std::to_string(s.id) + " <= 0");
    previous_x_ = Step(previous_x_, "start x");
    previous_y_ = Step(previous_y_, "start y");
    s.segment.start_m = {line_map::FromQuanta(previous_x_, q), line_map::FromQuanta(previous_y_, q)};
    s.segment.end_m = {line_map::FromQuanta(Step(previous_x_, "end x"), q),
                       line_map::FromQuanta(Step(previous_y_, "end y"), q)};
    s.support_cells = Count("support_cells");
    s.observations = Count("observations");
    s.rms_error_m = line_map::FromQuanta(static_cast<std::int64_t>(Count("rms error")),
                                         line_map::kRmsQuantumM);
    const std::uint64_t sources = in_.GetCount(1);
    for (std::uint64_t i = 0; i < sources && !in_.failed(); ++i) {
      const std::uint64_t index = in_.GetVarint();
      if (index >= table_.size()) {
        in_.Fail("provenance index " + std::to_string(index) + " beyond the table");
        break;
      }
      s.provenance.push_back(table_[static_cast<std::size_t>(index)]);
    }
    return s;
  }

  ByteReader& in_;
  std::vector<std::string> table_;
  std::int64_t previous_id_ = 0;
  std::int64_t previous_x_ = 0;
  std::int64_t previous_y_ = 0;
};

// Fails unless the whole input was read; returns whether it is good.
bool Finish(ByteReader& in, std::string* error) {
  if (!in.failed() && in.remaining() != 0) {
    in.Fail(std::to_string(in.remaining()) + " trailing bytes");
  }
  if (in.failed() && error != nullptr) *error = in.error();
  return !in.failed();
}

}  // namespace

std::string PackDelta(const line_map::MapDelta& delta) {
  SegmentPacker packer;
  packer.Collect(delta.added);
  packer.Collect(delta.changed);
  ByteWriter out;
  packer.PutTable(out);
  packer.Put(out, delta.added);
  packer.Put(out, delta.changed);
  out.PutVarint(delta.removed.size());
  std::int64_t previous = 0;
  for (std::int64_t id : delta.removed) {
    out.PutSigned(id - previous);
    previous = id;
  }
  return out.Take();
}

std::optional<line_map::MapDelta> UnpackDelta(std::string_view bytes, std::string* error) {
  ByteReader in(bytes);
  SegmentUnpacker unpacker(in);
  line_map::MapDelta delta;
  unpacker.GetTable();
  delta.added = unpacker.Get();
  delta.changed = unpacker.Get();
  const std::uint64_t removed = in.GetCount(1);
  std::int64_t previous = 0;
  for (std::uint64_t i = 0; i < removed && !in.failed(); ++i) {
    const std::int64_t step = in.GetSigned();
    if (step <= 0 || step > kMaxCoordinateQuanta) in.Fail("removed ids not increasing");
    previous += step;
    delta.removed.push_back(previous);
  }
  if (!Finish(in, error)) return std::nullopt;
  return delta;
}

std::string PackSnapshot(const line_map::MapSnapshot& snapshot) {
  SegmentPacker packer;
  packer.Collect(snapshot.segments);
  ByteWriter out;
  out.PutSigned(snapshot.next_id);
  packer.PutTable(out);
  packer.Put(out, snapshot.segments);
  return out.Take();
}

std::optional<line_map::MapSnapshot> UnpackSnapshot(std::string_view bytes, std::string* error) {
  ByteReader in(bytes);
  SegmentUnpacker unpacker(in);
  line_map::MapSnapshot snapshot;
  snapshot.next_id = in.GetSigned();
  unpacker.GetTable();
  snapshot.segments = unpacker.Get();
  if (!Finish(in, error)) return std::nullopt;
  return snapshot;
}

}  // namespace pena::gateway
