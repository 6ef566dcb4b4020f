// Received samples' Segment lists against their IDL bounds (dds_sample_bounds.hpp), through the
// type every Participant registers (CheckedType): real samples at the bounds pass unchanged, a
// provenance or segment list stated longer than its bound is refused before anything is sized.
#include <gtest/gtest.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "dds_participant.hpp"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"

namespace pena::services {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// 32 characters, the bound of a provenance entry; `tag` makes it findable in the payload.
std::string Entry(char tag, std::uint32_t i) {
  std::string entry = std::string(1, tag) + std::to_string(i);
  entry.resize(32, 'x');
  return entry;
}

// A segment with a full provenance list whose first entry starts with `tag`, and support.
pena_dds::Segment FullSegment(std::int64_t id, char tag) {
  pena_dds::Segment segment;
  segment.id(id);
  segment.start_x_mm(-1000);
  segment.end_x_mm(2500);
  segment.end_y_mm(7);
  segment.support_cells(40);
  segment.observations(120);
  segment.rms_error_100um(123);
  for (std::uint32_t i = 0; i < pena_dds::PROVENANCE_MAX; ++i) {
    segment.provenance().push_back(Entry(i == 0 ? tag : 'p', i).c_str());
  }
  // The global map's support after the provenance: a walk that did not step over it would read
  // the next list's length from it (3 + 12 x 65536, beyond every bound) and refuse a good sample.
  segment.seen_by_entities(3);
  segment.error_sd_cm(12);
  return segment;
}

template <class PubSubType>
SerializedPayload_t Serialize(typename PubSubType::type& sample) {
  PubSubType type;
  SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  EXPECT_TRUE(type.serialize(&sample, &payload));
  return payload;
}

// Deserializes through CheckedType; true and `out` filled if taken.
template <class PubSubType>
bool Take(SerializedPayload_t& payload, typename PubSubType::type& out) {
  CheckedType<PubSubType> type;
  return type.deserialize(&payload, &out);
}

// Writes `length` into the provenance count of the segment whose first entry starts with `tag`.
void StateProvenanceLength(SerializedPayload_t& payload, char tag, std::uint32_t length) {
  const std::string marker = Entry(tag, 0);
  const auto* begin = payload.data;
  const auto* end = payload.data + payload.length;
  const auto* found = std::search(begin, end, marker.begin(), marker.end());
  ASSERT_NE(found, end) << "marker not in the payload";
  // [count][string length][characters]: the count is 8 bytes before the first character.
  std::memcpy(payload.data + (found - begin) - 8, &length, sizeof(length));
}

TEST(SampleBounds, FullLineMapDeltaPassesUnchanged) {
  pena_dds::LineMapDelta sample;
  sample.entity_id("ff1");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  sample.from_version(4);
  sample.to_version(5);
  sample.added().push_back(FullSegment(1, 'A'));
  sample.changed().push_back(FullSegment(2, 'C'));
  sample.removed().push_back(3);
  sample.reference_scans_sent(9);
  SerializedPayload_t payload = Serialize<pena_dds::LineMapDeltaPubSubType>(sample);
  pena_dds::LineMapDelta taken;
  ASSERT_TRUE(Take<pena_dds::LineMapDeltaPubSubType>(payload, taken));
  EXPECT_EQ(taken, sample);
}

TEST(SampleBounds, ProvenanceStatedBeyondItsBoundIsRefusedInEveryList) {
  for (const char list : {'A', 'C'}) {
    pena_dds::LineMapDelta sample;
    sample.entity_id("ff1");
    sample.added().push_back(FullSegment(1, 'A'));
    sample.changed().push_back(FullSegment(2, 'C'));
    for (const std::uint32_t length : {pena_dds::PROVENANCE_MAX + 1, 0x7fffffffU, 0xffffffffU}) {
      SerializedPayload_t payload = Serialize<pena_dds::LineMapDeltaPubSubType>(sample);
      StateProvenanceLength(payload, list, length);
      pena_dds::LineMapDelta taken;
      // The walk itself refuses it (the generated code would size the list first).
      EXPECT_FALSE(SampleKeepsBounds(payload, &taken)) << "list " << list << ", length " << length;
      EXPECT_FALSE(Take<pena_dds::LineMapDeltaPubSubType>(payload, taken))
          << "list " << list << ", length " << length;
    }
  }
}

TEST(SampleBounds, SnapshotsAndGlobalMapsPassAtTheBoundAndRefuseBeyondIt) {
  pena_dds::LineMapSnapshot snapshot;
  snapshot.entity_id("ff1");
  snapshot.version(8);
  snapshot.next_id(3);
  snapshot.segments().push_back(FullSegment(1, 'S'));
  pena_dds::GlobalMapDelta global_delta;
  global_delta.map_id("global");
  global_delta.added().push_back(FullSegment(1, 'A'));
  global_delta.changed().push_back(FullSegment(2, 'C'));
  pena_dds::GlobalMapSnapshot global_snapshot;
  global_snapshot.map_id("global");
  global_snapshot.next_id(2);
  global_snapshot.segments().push_back(FullSegment(1, 'S'));

  SerializedPayload_t payload = Serialize<pena_dds::LineMapSnapshotPubSubType>(snapshot);
  pena_dds::LineMapSnapshot snapshot_taken;
  ASSERT_TRUE(Take<pena_dds::LineMapSnapshotPubSubType>(payload, snapshot_taken));
  EXPECT_EQ(snapshot_taken, snapshot);
  StateProvenanceLength(payload, 'S', pena_dds::PROVENANCE_MAX + 1);
  EXPECT_FALSE(Take<pena_dds::LineMapSnapshotPubSubType>(payload, snapshot_taken));

  // SerializedPayload_t's assignment copies the buffer pointer: one payload per sample.
  SerializedPayload_t delta_payload =
      Serialize<pena_dds::GlobalMapDeltaPubSubType>(global_delta);
  pena_dds::GlobalMapDelta global_delta_taken;
  ASSERT_TRUE(Take<pena_dds::GlobalMapDeltaPubSubType>(delta_payload, global_delta_taken));
  EXPECT_EQ(global_delta_taken, global_delta);
  StateProvenanceLength(delta_payload, 'C', pena_dds::PROVENANCE_MAX + 1);
  EXPECT_FALSE(Take<pena_dds::GlobalMapDeltaPubSubType>(delta_payload, global_delta_taken));

  SerializedPayload_t snapshot_payload =
      Serialize<pena_dds::GlobalMapSnapshotPubSubType>(global_snapshot);
  pena_dds::GlobalMapSnapshot global_snapshot_taken;
  ASSERT_TRUE(
      Take<pena_dds::GlobalMapSnapshotPubSubType>(snapshot_payload, global_snapshot_taken));
  EXPECT_EQ(global_snapshot_taken, global_snapshot);
  StateProvenanceLength(snapshot_payload, 'S', 0xffffffffU);
  EXPECT_FALSE(
      Take<pena_dds::GlobalMapSnapshotPubSubType>(snapshot_payload, global_snapshot_taken));
}

TEST(SampleBounds, OperatorCorrectionSegmentIsChecked) {
  pena_dds::OperatorCorrection sample;
  sample.correction_id("op/1");
  sample.operator_id("op");
  sample.kind(pena_dds::OPERATOR_ADD_SEGMENT);
  sample.target_entity_id("ff1");
  sample.stamp_s(3.5);
  sample.segment_id(7);
  sample.segment(FullSegment(1, 'O'));
  sample.refusal("none");
  SerializedPayload_t payload = Serialize<pena_dds::OperatorCorrectionPubSubType>(sample);
  pena_dds::OperatorCorrection taken;
  ASSERT_TRUE(Take<pena_dds::OperatorCorrectionPubSubType>(payload, taken));
  EXPECT_EQ(taken, sample);
  EXPECT_TRUE(SampleKeepsBounds(payload, &taken));
  StateProvenanceLength(payload, 'O', pena_dds::PROVENANCE_MAX + 1);
  EXPECT_FALSE(SampleKeepsBounds(payload, &taken));
  EXPECT_FALSE(Take<pena_dds::OperatorCorrectionPubSubType>(payload, taken));
}

TEST(SampleBounds, SegmentListBeyondItsBoundIsRefused) {
  pena_dds::LineMapSnapshot sample;
  sample.entity_id("ff1");
  SerializedPayload_t payload = Serialize<pena_dds::LineMapSnapshotPubSubType>(sample);
  // The empty list's length is the payload's last word.
  const std::uint32_t length = pena_dds::SNAPSHOT_MAX_SEGMENTS + 1;
  std::memcpy(payload.data + payload.length - 4, &length, sizeof(length));
  pena_dds::LineMapSnapshot taken;
  EXPECT_FALSE(Take<pena_dds::LineMapSnapshotPubSubType>(payload, taken));
}

}  // namespace
}  // namespace pena::services
