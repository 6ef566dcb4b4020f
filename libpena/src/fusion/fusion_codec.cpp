#include "pena/fusion/fusion_codec.hpp"

#include "byte_codec.hpp"
#include "fusion_fields.hpp"
#include "pena/io/input_error.hpp"

// Layout (docs/formats.md): u8 codec version, u8 kind (the FusionInput alternative's index, or
// 255 for a checkpoint), then the fields in declaration order. u64/i64/f64 little-endian (f64 by
// its IEEE bits), strings and lists as u64 count + items, optionals as u8 flag + value.

namespace pena::fusion {
namespace {

using detail::ByteReader;
using detail::ByteWriter;
using detail::GetAnnotation;
using detail::GetDelta;
using detail::GetOptionalPose;
using detail::GetPose;
using detail::GetSegments;
using detail::GetSnapshot;
using detail::Put;

constexpr std::uint8_t kCheckpointKind = 255;

// One function per input kind, writing the fields after the kind byte.
void PutFields(ByteWriter& w, const SetPlan& v) { Put(w, v.segments); }
void PutFields(ByteWriter& w, const EntityJoin& v) {
  w.Text(v.entity_id);
  Put(w, v.map_from_entity);
}
void PutFields(ByteWriter& w, const EntityLeave& v) { w.Text(v.entity_id); }
void PutFields(ByteWriter& w, const EntityHeartbeat& v) { w.Text(v.entity_id); }
void PutFields(ByteWriter& w, const LocalDelta& v) {
  w.Text(v.entity_id);
  Put(w, v.delta);
}
void PutFields(ByteWriter& w, const LocalSnapshot& v) {
  w.Text(v.entity_id);
  Put(w, v.snapshot);
}
void PutFields(ByteWriter& w, const AlignmentCorrection& v) {
  w.Text(v.entity_id);
  Put(w, v.map_from_entity);
  w.F64(v.confidence);
}
void PutFields(ByteWriter& w, const OperatorCorrection& v) {
  w.Text(v.entity_id);
  Put(w, v.corrected_from_wrong);
  w.Text(v.author);
}
void PutFields(ByteWriter& w, const PutAnnotation& v) { Put(w, v.annotation); }
void PutFields(ByteWriter& w, const RemoveAnnotation& v) {
  w.I64(v.annotation_id);
  w.Text(v.author);
}
void PutFields(ByteWriter&, const Tick&) {}
void PutFields(ByteWriter&, const Publish&) {}
void PutFields(ByteWriter& w, const MoveEntityWalls& v) {
  w.Text(v.entity_id);
  Put(w, v.corrected_from_wrong);
  w.U64(v.segment_ids.size());
  for (const std::int64_t id : v.segment_ids) w.I64(id);
  w.Text(v.author);
}

FusionInput GetInput(ByteReader& r, std::uint8_t kind, double stamp_s) {
  switch (kind) {
    case 0: return SetPlan{stamp_s, GetSegments(r)};
    case 1: {
      std::string id = r.Text();
      return EntityJoin{stamp_s, std::move(id), GetOptionalPose(r)};
    }
    case 2: return EntityLeave{stamp_s, r.Text()};
    case 3: return EntityHeartbeat{stamp_s, r.Text()};
    case 4: {
      std::string id = r.Text();
      return LocalDelta{stamp_s, std::move(id), GetDelta(r)};
    }
    case 5: {
      std::string id = r.Text();
      return LocalSnapshot{stamp_s, std::move(id), GetSnapshot(r)};
    }
    case 6: {
      AlignmentCorrection v{stamp_s, r.Text(), {}, 0.0};
      v.map_from_entity = GetPose(r);
      v.confidence = r.F64();
      return v;
    }
    case 7: {
      OperatorCorrection v{stamp_s, r.Text(), {}, {}};
      v.corrected_from_wrong = GetPose(r);
      v.author = r.Text();
      return v;
    }
    case 8: return PutAnnotation{stamp_s, GetAnnotation(r)};
    case 9: {
      RemoveAnnotation v{stamp_s, r.I64(), {}};
      v.author = r.Text();
      return v;
    }
    case 10: return Tick{stamp_s};
    case 11: return Publish{stamp_s};
    case 12: {
      MoveEntityWalls v{stamp_s, r.Text(), {}, {}, {}};
      v.corrected_from_wrong = GetPose(r);
      v.segment_ids.resize(r.Count(8));
      for (std::int64_t& id : v.segment_ids) id = r.I64();
      v.author = r.Text();
      return v;
    }
    default: r.Fail("unknown input kind " + std::to_string(kind));
  }
}

void PutStatus(ByteWriter& w, const EntityStatus& s) {
  w.Text(s.entity_id);
  w.U8(static_cast<std::uint8_t>(s.lifecycle));
  Put(w, s.map_from_entity);
  w.F64(s.last_data_s);
  w.U8(s.awaiting_snapshot ? 1 : 0);
  const PlacementResult& p = s.placement;
  w.U8(p.placed ? 1 : 0);
  w.U64(p.hypotheses.size());
  for (const PlacementHypothesis& h : p.hypotheses) {
    Put(w, h.map_from_entity);
    w.F64(h.score);
    w.F64(h.explained_m);
  }
  Put(w, p.map_from_entity);
  w.F64(p.margin_m);
  w.F64(p.local_length_m);
  w.Text(p.reason);
  w.F64(s.placement_length_m);
  w.U64(s.moved_walls.size());
  for (const auto& [id, move] : s.moved_walls) {
    w.I64(id);
    Put(w, move);
  }
}

EntityStatus GetStatus(ByteReader& r) {
  EntityStatus s;
  s.entity_id = r.Text();
  const std::uint8_t lifecycle = r.U8();
  if (lifecycle > static_cast<std::uint8_t>(EntityLifecycle::kLeft)) {
    r.Fail("unknown lifecycle " + std::to_string(lifecycle));
  }
  s.lifecycle = static_cast<EntityLifecycle>(lifecycle);
  s.map_from_entity = GetOptionalPose(r);
  s.last_data_s = r.F64();
  s.awaiting_snapshot = r.U8() != 0;
  PlacementResult& p = s.placement;
  p.placed = r.U8() != 0;
  p.hypotheses.resize(r.Count(5 * 8));
  for (PlacementHypothesis& h : p.hypotheses) {
    h.map_from_entity = GetPose(r);
    h.score = r.F64();
    h.explained_m = r.F64();
  }
  p.map_from_entity = GetPose(r);
  p.margin_m = r.F64();
  p.local_length_m = r.F64();
  p.reason = r.Text();
  s.placement_length_m = r.F64();
  if (r.version() >= 3) {  // before it, no walls were moved one by one
    const std::size_t moves = r.Count(4 * 8);
    for (std::size_t i = 0; i < moves; ++i) {
      const std::int64_t id = r.I64();
      s.moved_walls[id] = GetPose(r);
    }
  }
  return s;
}

// Runs `parse`, turning a ByteError or a leftover into io::InputError naming `name`.
template <typename Parse>
auto Decode(std::string_view bytes, const std::string& name, Parse parse) {
  ByteReader r(bytes);
  try {
    const std::uint8_t version = r.U8();
    if (version < 1 || version > kFusionCodecVersion) {
      r.Fail("encoding version " + std::to_string(version) + ", this reader knows 1 to " +
             std::to_string(kFusionCodecVersion));
    }
    r.set_version(version);
    auto value = parse(r);
    if (!r.done()) r.Fail("trailing bytes");
    return value;
  } catch (const detail::ByteError& error) {
    throw io::InputError(name, 0, "byte " + std::to_string(error.offset()) + ": " + error.what());
  }
}

}  // namespace

std::string EncodeInput(const FusionInput& input) {
  ByteWriter w;
  w.U8(kFusionCodecVersion);
  w.U8(static_cast<std::uint8_t>(input.index()));
  w.F64(StampOf(input));
  std::visit([&w](const auto& value) { PutFields(w, value); }, input);
  return w.Take();
}

FusionInput DecodeInput(std::string_view bytes, const std::string& name) {
  return Decode(bytes, name, [](ByteReader& r) {
    const std::uint8_t kind = r.U8();
    const double stamp_s = r.F64();
    return GetInput(r, kind, stamp_s);
  });
}

std::string EncodeCheckpoint(const FusionCheckpoint& c) {
  ByteWriter w;
  w.U8(kFusionCodecVersion);
  w.U8(kCheckpointKind);
  Put(w, c.plan);
  Put(w, c.global);
  w.U64(c.entities.size());
  for (const FusionCheckpoint::Entity& entity : c.entities) {
    PutStatus(w, entity.status);
    Put(w, entity.local);
  }
  w.U64(c.annotations.size());
  for (const Annotation& a : c.annotations) Put(w, a);
  w.U64(c.annotation_version);
  w.I64(c.next_annotation_id);
  w.U8(c.rebuild_pending ? 1 : 0);
  return w.Take();
}

FusionCheckpoint DecodeCheckpoint(std::string_view bytes, const std::string& name) {
  return Decode(bytes, name, [](ByteReader& r) {
    if (const std::uint8_t kind = r.U8(); kind != kCheckpointKind) {
      r.Fail("kind " + std::to_string(kind) + " is not a checkpoint");
    }
    FusionCheckpoint c;
    c.plan = GetSegments(r);
    c.global = GetSnapshot(r);
    c.entities.resize(r.Count(16));
    for (FusionCheckpoint::Entity& entity : c.entities) {
      entity.status = GetStatus(r);
      entity.local = GetSnapshot(r);
    }
    c.annotations.resize(r.Count(8 + 1 + 3 * 8 + 16 + 8));
    for (Annotation& a : c.annotations) a = GetAnnotation(r);
    c.annotation_version = r.U64();
    c.next_annotation_id = r.I64();
    c.rebuild_pending = r.U8() != 0;
    return c;
  });
}

}  // namespace pena::fusion
