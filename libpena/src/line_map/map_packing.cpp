#include "pena/line_map/map_packing.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "rice_coder.hpp"
#include "varint.hpp"

namespace pena::line_map {
namespace {

// Largest coordinate in quanta a packed segment may carry (kMaxCoordinateM in mm).
constexpr std::int64_t kMaxCoordinateQuanta = 2'000'000'000;
// Largest count (support cells, observations) a packed segment may carry.
constexpr std::int64_t kMaxCount = std::int64_t{1} << 50;
// Smallest packed segment: 11 fields of at least one bit each (see PutOne).
constexpr std::uint64_t kMinSegmentBits = 11;

// The quanta of `value_m`, throwing if it is not an exact multiple (what LineMap stores) or lies
// beyond what a LineMap holds.
std::int64_t ExactQuanta(double value_m, double quantum_m, const char* what) {
  if (!(std::abs(value_m) <= kMaxCoordinateM)) {
    throw std::invalid_argument(std::string("map packing: ") + what + " " +
                                std::to_string(value_m) + " is beyond the map's range");
  }
  const std::int64_t quanta = ToQuanta(value_m, quantum_m);
  if (FromQuanta(quanta, quantum_m) != value_m) {
    throw std::invalid_argument(std::string("map packing: ") + what + " " +
                                std::to_string(value_m) + " is not on the map's quanta");
  }
  return quanta;
}

std::int64_t ExactCount(double count, const char* what) {
  if (!(count >= 0.0) || count != std::floor(count) || count > static_cast<double>(kMaxCount)) {
    throw std::invalid_argument(std::string("map packing: ") + what + " " + std::to_string(count) +
                                " is not a whole count in [0, 2^50]");
  }
  return static_cast<std::int64_t>(count);
}

// One Rice context per field, each with a prior near the field's typical value in a building map
// (millimetres, 0.1 mm for the fit error), so short deltas code well before the contexts adapt.
struct FieldContexts {
  RiceContext count{64};
  RiceContext text_length{8};
  RiceContext sources{1};
  RiceContext source_index{2};
  RiceContext id_step{1};
  RiceContext start_x{8192};
  RiceContext start_y{8192};
  RiceContext major{1024};
  RiceContext minor{128};
  RiceContext support{32};
  RiceContext extra_observations{64};
  RiceContext rms{256};
  RiceContext next_id{256};
  RiceContext removed_step{4};
  RiceContext seen_by{1};
  RiceContext error_sd{16};
};

// Writes segments with ids and starts relative to the previous one, the end relative to its own
// start (the longer axis as sign and magnitude, the shorter zig-zag), observations as the excess
// over support_cells, and provenance as table indices, or one bit when the previous segment's
// list repeats. A global wall's support (seen_by_entities, error sd in cm) follows only when the
// message says so: one bit per message, so an entity's map pays nothing for it.
class SegmentPacker {
 public:
  SegmentPacker(BitWriter& out, FieldContexts& contexts) : out_(out), c_(contexts) {}
  void Collect(const std::vector<LineSegment>& segments) {
    for (const LineSegment& segment : segments) {
      for (const std::string& source : segment.provenance) table_.emplace(source, table_.size());
      with_support_ = with_support_ || segment.seen_by_entities != 0 || segment.error_sd_m != 0.0;
    }
  }
  void PutTable() {
    std::vector<const std::string*> ordered(table_.size());
    for (const auto& [text, index] : table_) ordered[index] = &text;
    out_.PutRice(c_.count, ordered.size());
    for (const std::string* text : ordered) out_.PutText(c_.text_length, *text);
    out_.PutBit(with_support_);
  }
  void Put(const std::vector<LineSegment>& segments) {
    out_.PutRice(c_.count, segments.size());
    for (const LineSegment& segment : segments) PutOne(segment);
  }

 private:
  void PutOne(const LineSegment& s) {
    const double q = kCoordinateQuantumM;
    if (s.id <= 0) throw std::invalid_argument("map packing: segment id must be > 0");
    const std::int64_t sx = ExactQuanta(s.segment.start_m.x(), q, "start x");
    const std::int64_t sy = ExactQuanta(s.segment.start_m.y(), q, "start y");
    const std::int64_t dx = ExactQuanta(s.segment.end_m.x(), q, "end x") - sx;
    const std::int64_t dy = ExactQuanta(s.segment.end_m.y(), q, "end y") - sy;
    const std::int64_t support = ExactCount(s.support_cells, "support_cells");
    const std::int64_t observations = ExactCount(s.observations, "observations");
    const std::int64_t rms = ExactQuanta(s.rms_error_m, kRmsQuantumM, "rms error");
    if (rms < 0 || rms > kMaxCount) throw std::invalid_argument("map packing: bad rms error");
    out_.PutRice(c_.id_step, ZigZag(s.id - previous_id_ - 1));
    const bool same_sources = s.provenance == previous_sources_;
    out_.PutBit(same_sources);
    if (!same_sources) {
      out_.PutRice(c_.sources, s.provenance.size());
      for (const std::string& source : s.provenance) out_.PutRice(c_.source_index, table_.at(source));
    }
    out_.PutRice(c_.start_x, ZigZag(sx - previous_x_));
    out_.PutRice(c_.start_y, ZigZag(sy - previous_y_));
    const bool x_major = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t major = x_major ? dx : dy;
    out_.PutBit(x_major);
    out_.PutBit(major < 0);
    out_.PutRice(c_.major, static_cast<std::uint64_t>(std::llabs(major)));
    out_.PutRice(c_.minor, ZigZag(x_major ? dy : dx));
    out_.PutRice(c_.support, static_cast<std::uint64_t>(support));
    out_.PutRice(c_.extra_observations, ZigZag(observations - support));
    out_.PutRice(c_.rms, static_cast<std::uint64_t>(rms));
    if (with_support_) {
      const std::int64_t sd = ExactQuanta(s.error_sd_m, kErrorSdQuantumM, "error sd");
      if (sd < 0 || s.error_sd_m > kMaxErrorSdM) {
        throw std::invalid_argument("map packing: error sd must be in [0, 655.35] m");
      }
      out_.PutRice(c_.seen_by, s.seen_by_entities);
      out_.PutRice(c_.error_sd, static_cast<std::uint64_t>(sd));
    }
    previous_id_ = s.id;
    previous_x_ = sx;
    previous_y_ = sy;
    previous_sources_ = s.provenance;
  }

  BitWriter& out_;
  FieldContexts& c_;
  std::map<std::string, std::size_t> table_;
  bool with_support_ = false;
  std::int64_t previous_id_ = 0;
  std::int64_t previous_x_ = 0;
  std::int64_t previous_y_ = 0;
  std::vector<std::string> previous_sources_;
};

// The inverse of SegmentPacker; every value is range-checked so no input overflows.
class SegmentUnpacker {
 public:
  SegmentUnpacker(BitReader& in, FieldContexts& contexts) : in_(in), c_(contexts) {}
  void GetTable() {
    const std::uint64_t count = in_.GetCount(c_.count, 1);
    for (std::uint64_t i = 0; i < count && !in_.failed(); ++i) {
      table_.push_back(in_.GetText(c_.text_length));
    }
    with_support_ = in_.GetBit();
  }
  std::vector<LineSegment> Get() {
    const std::uint64_t count = in_.GetCount(c_.count, kMinSegmentBits);
    std::vector<LineSegment> segments;
    segments.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count && !in_.failed(); ++i) segments.push_back(GetOne());
    return segments;
  }

 private:
  // `previous` plus a zig-zag step, both within +-limit.
  std::int64_t Step(RiceContext& context, std::int64_t previous, std::int64_t limit,
                    const char* what) {
    const std::int64_t delta = UnZigZag(in_.GetRice(context));
    if (delta > 2 * limit || delta < -2 * limit) {
      in_.Fail(std::string(what) + " step out of range");
      return 0;
    }
    const std::int64_t value = previous + delta;
    if (value > limit || value < -limit) {
      in_.Fail(std::string(what) + " out of range");
      return 0;
    }
    return value;
  }
  std::int64_t Count(RiceContext& context, const char* what) {
    const std::uint64_t value = in_.GetRice(context);
    if (value > static_cast<std::uint64_t>(kMaxCount)) {
      in_.Fail(std::string(what) + " out of range");
      return 0;
    }
    return static_cast<std::int64_t>(value);
  }
  void GetSources(LineSegment& s) {
    if (in_.GetBit()) {
      s.provenance = previous_sources_;
      return;
    }
    const std::uint64_t sources = in_.GetCount(c_.sources, 1);
    for (std::uint64_t i = 0; i < sources && !in_.failed(); ++i) {
      const std::uint64_t index = in_.GetRice(c_.source_index);
      if (index >= table_.size()) {
        in_.Fail("provenance index " + std::to_string(index) + " beyond the table");
        break;
      }
      s.provenance.push_back(table_[static_cast<std::size_t>(index)]);
    }
  }
  LineSegment GetOne() {
    const double q = kCoordinateQuantumM;
    LineSegment s;
    previous_id_ = Step(c_.id_step, previous_id_ + 1, kMaxCoordinateQuanta, "id");
    s.id = previous_id_;
    if (s.id <= 0 && !in_.failed()) in_.Fail("segment id " + std::to_string(s.id) + " <= 0");
    GetSources(s);
    previous_sources_ = s.provenance;
    previous_x_ = Step(c_.start_x, previous_x_, kMaxCoordinateQuanta, "start x");
    previous_y_ = Step(c_.start_y, previous_y_, kMaxCoordinateQuanta, "start y");
    const bool x_major = in_.GetBit();
    const bool negative = in_.GetBit();
    const std::int64_t magnitude = Count(c_.major, "end step");
    const std::int64_t major = negative ? -magnitude : magnitude;
    const std::int64_t minor = Step(c_.minor, 0, 2 * kMaxCoordinateQuanta, "end step");
    const std::int64_t ex = x_major ? major : minor;
    const std::int64_t ey = x_major ? minor : major;
    s.segment.start_m = {FromQuanta(previous_x_, q), FromQuanta(previous_y_, q)};
    s.segment.end_m = {FromQuanta(Bounded(previous_x_ + ex, "end x"), q),
                       FromQuanta(Bounded(previous_y_ + ey, "end y"), q)};
    const std::int64_t support = Count(c_.support, "support_cells");
    s.support_cells = static_cast<double>(support);
    const std::int64_t observations =
        Step(c_.extra_observations, support, kMaxCount, "observations");
    if (observations < 0 && !in_.failed()) in_.Fail("observations < 0");
    s.observations = static_cast<double>(observations);
    s.rms_error_m = FromQuanta(Count(c_.rms, "rms error"), kRmsQuantumM);
    if (with_support_) GetSupport(s);
    return s;
  }
  void GetSupport(LineSegment& s) {
    const std::uint64_t seen_by = in_.GetRice(c_.seen_by);
    const std::uint64_t sd = in_.GetRice(c_.error_sd);
    const auto max_sd = static_cast<std::uint64_t>(ToQuanta(kMaxErrorSdM, kErrorSdQuantumM));
    if (seen_by > std::numeric_limits<std::uint32_t>::max() || sd > max_sd) {
      if (!in_.failed()) in_.Fail("wall support out of range");
      return;
    }
    s.seen_by_entities = static_cast<std::uint32_t>(seen_by);
    s.error_sd_m = FromQuanta(static_cast<std::int64_t>(sd), kErrorSdQuantumM);
  }
  std::int64_t Bounded(std::int64_t value, const char* what) {
    if (value > kMaxCoordinateQuanta || value < -kMaxCoordinateQuanta) {
      in_.Fail(std::string(what) + " out of range");
      return 0;
    }
    return value;
  }

  BitReader& in_;
  FieldContexts& c_;
  std::vector<std::string> table_;
  bool with_support_ = false;
  std::int64_t previous_id_ = 0;
  std::int64_t previous_x_ = 0;
  std::int64_t previous_y_ = 0;
  std::vector<std::string> previous_sources_;
};

// Fails unless the whole input was read; returns whether it is good.
bool Finish(BitReader& in, std::string* error) {
  in.Finish();
  if (in.failed() && error != nullptr) *error = in.error();
  return !in.failed();
}

}  // namespace

std::string PackDelta(const MapDelta& delta) {
  BitWriter out;
  FieldContexts contexts;
  SegmentPacker packer(out, contexts);
  packer.Collect(delta.added);
  packer.Collect(delta.changed);
  packer.PutTable();
  packer.Put(delta.added);
  packer.Put(delta.changed);
  out.PutRice(contexts.count, delta.removed.size());
  std::int64_t previous = 0;
  for (std::int64_t id : delta.removed) {
    if (id <= previous) throw std::invalid_argument("map packing: removed ids not increasing");
    out.PutRice(contexts.removed_step, static_cast<std::uint64_t>(id - previous - 1));
    previous = id;
  }
  return out.Take();
}

std::optional<MapDelta> UnpackDelta(std::string_view bytes, std::string* error) {
  BitReader in(bytes);
  FieldContexts contexts;
  SegmentUnpacker unpacker(in, contexts);
  MapDelta delta;
  unpacker.GetTable();
  delta.added = unpacker.Get();
  delta.changed = unpacker.Get();
  const std::uint64_t removed = in.GetCount(contexts.count, 1);
  std::int64_t previous = 0;
  for (std::uint64_t i = 0; i < removed && !in.failed(); ++i) {
    const std::uint64_t step = in.GetRice(contexts.removed_step);
    if (step >= static_cast<std::uint64_t>(kMaxCoordinateQuanta) ||
        previous + 1 + static_cast<std::int64_t>(step) > kMaxCoordinateQuanta) {
      in.Fail("removed id out of range");
      break;
    }
    previous += 1 + static_cast<std::int64_t>(step);
    delta.removed.push_back(previous);
  }
  if (!Finish(in, error)) return std::nullopt;
  return delta;
}

std::string PackSnapshot(const MapSnapshot& snapshot) {
  BitWriter out;
  FieldContexts contexts;
  SegmentPacker packer(out, contexts);
  packer.Collect(snapshot.segments);
  out.PutRice(contexts.next_id, ZigZag(snapshot.next_id));
  packer.PutTable();
  packer.Put(snapshot.segments);
  return out.Take();
}

std::optional<MapSnapshot> UnpackSnapshot(std::string_view bytes, std::string* error) {
  BitReader in(bytes);
  FieldContexts contexts;
  SegmentUnpacker unpacker(in, contexts);
  MapSnapshot snapshot;
  snapshot.next_id = UnZigZag(in.GetRice(contexts.next_id));
  unpacker.GetTable();
  snapshot.segments = unpacker.Get();
  if (!Finish(in, error)) return std::nullopt;
  return snapshot;
}

}  // namespace pena::line_map
