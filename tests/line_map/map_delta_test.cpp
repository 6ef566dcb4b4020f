#include <gtest/gtest.h>

#include <optional>

#include "loop_walls.hpp"
#include "pena/io/line_map_codec.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::line_map {
namespace {

using testing::Piece;

// The deltas of a sender walking the loop three times, and the sender at the end.
struct Stream {
  LineMap sender;
  std::vector<MapDelta> deltas;
  std::vector<MapSnapshot> snapshots;  // sender's snapshot after each delta
};

MapDelta Versions(std::uint64_t from, std::uint64_t to) {
  MapDelta delta;
  delta.from_version = from;
  delta.to_version = to;
  return delta;
}

Stream WalkAndRecord() {
  Stream stream;
  for (const auto& batch : testing::WalkLoop(3, 0.02, 11)) {
    MapDelta delta = stream.sender.Integrate(batch, "ff1");
    if (delta.empty()) continue;
    stream.deltas.push_back(std::move(delta));
    stream.snapshots.push_back(stream.sender.Snapshot());
  }
  return stream;
}

TEST(MapDelta, ReplayIntoEmptyMapReproducesFinalMapExactly) {
  const Stream stream = WalkAndRecord();
  ASSERT_GT(stream.deltas.size(), 10u);
  LineMap receiver;
  for (const MapDelta& delta : stream.deltas) {
    const ApplyResult result = receiver.Apply(delta);
    ASSERT_TRUE(result.ok()) << result.message;
  }
  EXPECT_TRUE(SameMap(receiver.Snapshot(), stream.sender.Snapshot()));
  EXPECT_EQ(receiver.version(), stream.deltas.size());
}

TEST(MapDelta, ReplayThroughWireEncodingIsExact) {
  const Stream stream = WalkAndRecord();
  LineMap receiver;
  for (const MapDelta& delta : stream.deltas) {
    ASSERT_TRUE(receiver.Apply(io::DecodeDelta(io::EncodeDelta(delta))).ok());
  }
  EXPECT_TRUE(SameMap(receiver.Snapshot(), stream.sender.Snapshot()));
}

TEST(MapDelta, DetectsDroppedDeltaAndRecoversFromSnapshot) {
  const Stream stream = WalkAndRecord();
  const std::size_t dropped = 5;
  const std::size_t snapshot_after = 8;  // the sender's answer arrives a few deltas later
  ASSERT_GT(stream.deltas.size(), snapshot_after + 2);
  std::optional<LineMap> receiver(std::in_place);
  for (std::size_t i = 0; i < stream.deltas.size(); ++i) {
    if (i == dropped) continue;
    if (i == snapshot_after + 1) {
      const std::string bytes = io::EncodeSnapshot(stream.snapshots[snapshot_after]);
      receiver = LineMap::FromSnapshot(io::DecodeSnapshot(bytes));
      // Deltas still in flight from before the snapshot are recognised as already contained.
      EXPECT_EQ(receiver->Apply(stream.deltas[snapshot_after]).status, ApplyStatus::kStale);
    }
    const MapSnapshot before = receiver->Snapshot();
    const ApplyResult result = receiver->Apply(stream.deltas[i]);
    if (i > dropped && i <= snapshot_after) {
      EXPECT_EQ(result.status, ApplyStatus::kVersionGap) << "delta " << i;
      EXPECT_TRUE(SameMap(before, receiver->Snapshot()));
    } else {
      ASSERT_TRUE(result.ok()) << "delta " << i << ": " << result.message;
    }
  }
  EXPECT_TRUE(SameMap(receiver->Snapshot(), stream.sender.Snapshot()));
}

TEST(MapDelta, SenderResumedFromSnapshotProducesTheSameDeltas) {
  const auto batches = testing::WalkLoop(2, 0.02, 5);
  LineMap original;
  for (std::size_t i = 0; i < batches.size() / 2; ++i) original.Integrate(batches[i], "ff1");
  LineMap resumed = LineMap::FromSnapshot(original.Snapshot());
  for (std::size_t i = batches.size() / 2; i < batches.size(); ++i) {
    const MapDelta a = original.Integrate(batches[i], "ff1");
    const MapDelta b = resumed.Integrate(batches[i], "ff1");
    ASSERT_EQ(io::EncodeDelta(a), io::EncodeDelta(b)) << "batch " << i;
  }
}

TEST(MapDelta, ListsAddedChangedAndRemovedById) {
  LineMap map;
  const MapDelta first = map.Integrate({Piece(0, 0, 3, 0), Piece(3.6, 0, 6, 0)}, "ff1");
  EXPECT_EQ(first.from_version, 0u);
  EXPECT_EQ(first.to_version, 1u);
  ASSERT_EQ(first.added.size(), 2u);
  EXPECT_EQ(first.added[0].id, 1);
  EXPECT_EQ(first.added[1].id, 2);
  const MapDelta second = map.Integrate({Piece(2.5, 0, 4, 0), Piece(0, 4, 4, 4)}, "ff1");
  EXPECT_EQ(second.from_version, 1u);
  EXPECT_EQ(second.to_version, 2u);
  ASSERT_EQ(second.added.size(), 1u);
  EXPECT_EQ(second.added[0].id, 3);
  ASSERT_EQ(second.changed.size(), 1u);
  EXPECT_EQ(second.changed[0].id, 1);
  EXPECT_EQ(second.removed, (std::vector<std::int64_t>{2}));
}

TEST(MapDelta, EmptyBatchKeepsVersion) {
  LineMap map;
  map.Integrate({Piece(0, 0, 4, 0, 0.0)}, "ff1");
  const MapDelta nothing = map.Integrate({}, "ff1");
  EXPECT_TRUE(nothing.empty());
  EXPECT_EQ(nothing.from_version, 1u);
  EXPECT_EQ(nothing.to_version, 1u);
  EXPECT_EQ(map.version(), 1u);
  LineMap receiver;
  EXPECT_EQ(receiver.Apply(nothing).status, ApplyStatus::kVersionGap);
}

TEST(MapDelta, RefusesInconsistentDeltasAndLeavesMapUnchanged) {
  LineMap sender;
  LineMap receiver;
  ASSERT_TRUE(receiver.Apply(sender.Integrate({Piece(0, 0, 4, 0)}, "ff1")).ok());
  const MapSnapshot before = receiver.Snapshot();
  MapDelta unknown = Versions(1, 2);
  unknown.changed.push_back(Piece(0, 0, 5, 0));
  unknown.changed.back().id = 42;
  EXPECT_EQ(receiver.Apply(unknown).status, ApplyStatus::kInvalid);
  MapDelta again = Versions(1, 2);
  again.added.push_back(receiver.segments().front());
  EXPECT_EQ(receiver.Apply(again).status, ApplyStatus::kInvalid);
  MapDelta jump = Versions(1, 3);
  jump.removed = {1};
  EXPECT_EQ(receiver.Apply(jump).status, ApplyStatus::kInvalid);
  MapDelta twice = Versions(1, 2);
  twice.removed = {1, 1};
  EXPECT_EQ(receiver.Apply(twice).status, ApplyStatus::kInvalid);
  EXPECT_TRUE(SameMap(before, receiver.Snapshot()));
}

TEST(MapDelta, RejectsSnapshotWithDuplicateIdsOrStaleNextId) {
  MapSnapshot snapshot;
  snapshot.version = 3;
  snapshot.next_id = 5;
  snapshot.segments = {Piece(0, 0, 1, 0)};
  snapshot.segments.front().id = 4;
  EXPECT_NO_THROW(LineMap::FromSnapshot(snapshot));
  snapshot.next_id = 4;
  EXPECT_THROW(LineMap::FromSnapshot(snapshot), std::invalid_argument);
  snapshot.next_id = 5;
  snapshot.segments.push_back(snapshot.segments.front());
  EXPECT_THROW(LineMap::FromSnapshot(snapshot), std::invalid_argument);
}

}  // namespace
}  // namespace pena::line_map
