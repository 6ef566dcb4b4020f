#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>
#include <stdexcept>

#include "loop_walls.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_map_codec.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::line_map {
namespace {

using testing::Piece;

MapDelta BridgeDelta() {
  LineMap map;
  map.Integrate({Piece(0, 0, 3, 0), Piece(3.6, 0, 6, 0)}, "ff1");
  return map.Integrate({Piece(2.5, 0.01, 4, 0), Piece(-1.5, -7.25, 4.125, 3.5)}, "robot1");
}

void ExpectSameDelta(const MapDelta& a, const MapDelta& b) {
  EXPECT_EQ(a.from_version, b.from_version);
  EXPECT_EQ(a.to_version, b.to_version);
  ASSERT_EQ(a.added.size(), b.added.size());
  ASSERT_EQ(a.changed.size(), b.changed.size());
  for (std::size_t i = 0; i < a.added.size(); ++i) EXPECT_TRUE(SameSegment(a.added[i], b.added[i]));
  for (std::size_t i = 0; i < a.changed.size(); ++i) {
    EXPECT_TRUE(SameSegment(a.changed[i], b.changed[i]));
  }
  EXPECT_EQ(a.removed, b.removed);
}

TEST(LineMapCodec, RoundTripsDeltaExactly) {
  const MapDelta delta = BridgeDelta();
  ASSERT_FALSE(delta.added.empty());
  ASSERT_FALSE(delta.changed.empty());
  ASSERT_FALSE(delta.removed.empty());
  ExpectSameDelta(io::DecodeDelta(io::EncodeDelta(delta)), delta);
}

TEST(LineMapCodec, RoundTripsSnapshotExactly) {
  LineMap map;
  for (const auto& batch : testing::WalkLoop(1, 0.02, 3)) map.Integrate(batch, "ff1");
  const MapSnapshot snapshot = map.Snapshot();
  const MapSnapshot decoded = io::DecodeSnapshot(io::EncodeSnapshot(snapshot));
  EXPECT_TRUE(SameMap(decoded, snapshot));
  EXPECT_EQ(decoded.next_id, snapshot.next_id);
}

TEST(LineMapCodec, RoundTripsAGlobalWallsSupport) {
  LineMap map;
  for (const auto& batch : testing::WalkLoop(1, 0.02, 1)) map.Integrate(batch, "ff1");
  MapSnapshot snapshot = map.Snapshot();
  ASSERT_GE(snapshot.segments.size(), 2u);
  snapshot.segments[0].seen_by_entities = 3;
  snapshot.segments[0].error_sd_m = Quantise(0.17, kErrorSdQuantumM);
  snapshot.segments[1].seen_by_entities = 1;
  snapshot.segments[1].error_sd_m = kMaxErrorSdM;
  const MapSnapshot decoded = io::DecodeSnapshot(io::EncodeSnapshot(snapshot));
  EXPECT_TRUE(SameMap(decoded, snapshot));
  EXPECT_EQ(decoded.segments[0].seen_by_entities, 3u);
  EXPECT_EQ(decoded.segments[1].error_sd_m, kMaxErrorSdM);
  snapshot.segments[1].error_sd_m = 0.125;  // not whole centimetres
  EXPECT_THROW(io::EncodeSnapshot(snapshot), std::invalid_argument);
}

void ExpectRejected(const std::string& bytes, const std::string& why) {
  EXPECT_THROW(io::DecodeDelta(bytes, "link"), io::InputError) << why;
  EXPECT_THROW(io::DecodeSnapshot(bytes, "link"), io::InputError) << why;
}

TEST(LineMapCodec, RejectsGarbageTruncationAndOtherSchemaVersions) {
  ExpectRejected("", "empty: no schema version");
  ExpectRejected("this is not a line map", "text");
  std::mt19937 random(1);
  for (int trial = 0; trial < 50; ++trial) {
    std::string bytes(20 + static_cast<std::size_t>(trial), '\0');
    for (char& c : bytes) c = static_cast<char>(random() & 0xFFu);
    ExpectRejected(bytes, "random bytes, trial " + std::to_string(trial));
  }
  MapDelta added_only;
  added_only.to_version = 1;
  added_only.added.push_back(Piece(0, 0, 2, 0));
  added_only.added.back().id = 1;
  std::string bytes = io::EncodeDelta(added_only);
  EXPECT_THROW(io::DecodeDelta(bytes.substr(0, bytes.size() - 1)), io::InputError);
  ASSERT_EQ(bytes.substr(0, 2), std::string("\x08\x01"));  // schema_version = 1 comes first
  bytes[1] = '\x02';
  try {
    io::DecodeDelta(bytes, "link");
    FAIL() << "accepted schema version 2";
  } catch (const io::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("link:0: schema_version 2"), std::string::npos)
        << error.what();
  }
}

TEST(LineMapCodec, RejectsNonPositiveIdOnTheWire) {
  MapDelta delta;
  delta.to_version = 1;
  delta.added.push_back(Piece(0, 0, 2, 0));
  delta.added.back().id = 0;
  EXPECT_THROW(io::EncodeDelta(delta), std::invalid_argument);
}

TEST(LineMapCodec, RefusesValuesTheWireCannotCarryExactly) {
  MapDelta delta;
  delta.to_version = 1;
  delta.added.push_back(Piece(0.0005, 0, 2, 0));
  delta.added.back().id = 1;
  EXPECT_THROW(io::EncodeDelta(delta), std::invalid_argument);
  delta.added.back() = Piece(0, 0, 2, 0, 2.5);
  delta.added.back().id = 1;
  EXPECT_THROW(io::EncodeDelta(delta), std::invalid_argument);
}

// Bytes per delta of a sender walking the loop three times (docs/line-map.md quotes the output).
TEST(LineMapCodec, DeltasOfALoopWalkStaySmall) {
  LineMap map;
  std::size_t deltas = 0;
  std::size_t delta_bytes = 0;
  std::size_t largest_bytes = 0;
  std::size_t segments_sent = 0;
  for (const auto& batch : testing::WalkLoop(3, 0.02, 9)) {
    const MapDelta delta = map.Integrate(batch, "ff1");
    if (delta.empty()) continue;
    const std::size_t bytes = io::EncodeDelta(delta).size();
    ++deltas;
    delta_bytes += bytes;
    largest_bytes = std::max(largest_bytes, bytes);
    segments_sent += delta.added.size() + delta.changed.size();
  }
  const std::size_t snapshot_bytes = io::EncodeSnapshot(map.Snapshot()).size();
  const double per_delta = static_cast<double>(delta_bytes) / static_cast<double>(deltas);
  const double per_segment = static_cast<double>(delta_bytes) / static_cast<double>(segments_sent);
  const double per_snapshot_segment =
      static_cast<double>(snapshot_bytes) / static_cast<double>(map.size());
  std::cout << "deltas " << deltas << ", mean " << per_delta << " B, largest " << largest_bytes
            << " B, " << per_segment << " B per segment sent; snapshot of " << map.size()
            << " segments " << snapshot_bytes << " B (" << per_snapshot_segment
            << " B per segment)\n";
  ::testing::Test::RecordProperty("bytes_per_delta", std::to_string(per_delta));
  ::testing::Test::RecordProperty("bytes_per_segment", std::to_string(per_segment));
  // A segment is an id, four millimetre varints, three counts and the source name.
  EXPECT_LT(per_snapshot_segment, 40.0);
  EXPECT_LT(per_segment, 40.0);
}

}  // namespace
}  // namespace pena::line_map
