// The map packing's codes (varints, adaptive Rice codes) at their extremes, and map packing of
// values at the edges of what a LineMap holds; tests/gateway packs a team's real deltas.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pena/line_map/internal/rice_coder.hpp"
#include "pena/line_map/internal/varint.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/line_map/map_packing.hpp"

namespace pena::line_map {
namespace {

TEST(Varint, RoundTripsExtremesAndZigZag) {
  ByteWriter out;
  const std::vector<std::int64_t> values = {0, 1, -1, 63, -64, 300, -300, INT64_MAX, INT64_MIN};
  for (std::int64_t value : values) out.PutSigned(value);
  out.PutVarint(UINT64_MAX);
  ByteReader in(out.bytes());
  for (std::int64_t value : values) EXPECT_EQ(in.GetSigned(), value);
  EXPECT_EQ(in.GetVarint(), UINT64_MAX);
  EXPECT_FALSE(in.failed());
  EXPECT_EQ(in.remaining(), 0U);
  EXPECT_EQ(ZigZag(-1), 1U);
  EXPECT_EQ(ZigZag(1), 2U);
}

TEST(Varint, ReaderFailsOnTruncatedAndOverlongInput) {
  const std::string truncated_bytes("\x80\x80", 2);
  const std::string overlong_bytes(11, '\xff');
  const std::string too_many_bytes("\x05\x01", 2);
  ByteReader truncated(truncated_bytes);
  EXPECT_EQ(truncated.GetVarint(), 0U);
  EXPECT_TRUE(truncated.failed());
  ByteReader overlong(overlong_bytes);
  overlong.GetVarint();
  EXPECT_TRUE(overlong.failed());
  ByteReader too_many(too_many_bytes);
  EXPECT_EQ(too_many.GetCount(1), 0U);  // 5 things cannot fit in 1 byte
  EXPECT_TRUE(too_many.failed());
}

TEST(RiceCoder, RoundTripsExtremesEscapesAndAdaptation) {
  std::vector<std::uint64_t> values = {0, 1, 2, 3, 255, 256, 4095, 1U << 20, UINT64_MAX, 0, 7};
  for (std::uint64_t i = 0; i < 300; ++i) values.push_back((i * 2654435761U) % (std::uint64_t{1} << (i % 40)));
  BitWriter out;
  RiceContext written(16);
  for (std::uint64_t value : values) out.PutRice(written, value);
  out.PutBits(0x5, 3);
  out.PutText(written, std::string("ff1\0x", 5));
  const std::string bytes = out.Take();
  BitReader in(bytes);
  RiceContext read(16);
  for (std::uint64_t value : values) EXPECT_EQ(in.GetRice(read), value);
  EXPECT_EQ(in.GetBits(3), 0x5U);
  EXPECT_EQ(in.GetText(read), std::string("ff1\0x", 5));
  EXPECT_TRUE(in.Finish()) << in.error();
  EXPECT_EQ(read.k(), written.k());
}

TEST(RiceCoder, ReaderFailsOnTruncationTrailingBytesAndBadPadding) {
  BitWriter out;
  RiceContext context(1);
  out.PutRice(context, 100);  // an escape at k = 0: 37 bits, 3 of padding
  const std::string bytes = out.Take();
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    RiceContext again(1);
    BitReader in(std::string_view(bytes).substr(0, size));
    in.GetRice(again);
    EXPECT_TRUE(in.failed()) << "size " << size;
  }
  RiceContext again(1);
  const std::string with_trailing = bytes + "x";  // BitReader views its input: keep it alive
  BitReader trailing(with_trailing);
  EXPECT_EQ(trailing.GetRice(again), 100U);
  EXPECT_FALSE(trailing.Finish());
  EXPECT_NE(trailing.error().find("trailing"), std::string::npos);
  const std::string ones_bytes(2, '\xff');  // 16 one-bits: a quotient cut short
  BitReader all_ones(ones_bytes);
  RiceContext ones(1);
  all_ones.GetRice(ones);
  EXPECT_TRUE(all_ones.failed());
  std::string padded = bytes;
  padded.back() = static_cast<char>(padded.back() | 1);  // a set padding bit
  RiceContext third(1);
  BitReader bad_padding(padded);
  bad_padding.GetRice(third);
  EXPECT_FALSE(bad_padding.Finish());
}

TEST(MapPacking, RefusesValuesOffTheMapQuanta) {
  MapDelta delta;
  LineSegment segment;
  segment.id = 1;
  segment.segment.end_m = {0.0005, 0.0};
  delta.added.push_back(segment);
  EXPECT_THROW(PackDelta(delta), std::invalid_argument);
}

// Values at the edges of what a LineMap can hold, sparse ids, every direction of the end, and
// provenance lists that repeat, change and are empty.
TEST(MapPacking, SnapshotWithExtremeValuesRoundTripsExactly) {
  MapSnapshot snapshot;
  snapshot.next_id = 5'000'001;
  const std::vector<std::vector<std::string>> sources = {{"ff1"}, {"ff1"}, {}, {"ff2", "#3", "ff1"}};
  const double far_m = kMaxCoordinateM;
  const std::vector<std::array<double, 4>> ends = {{0.0, 0.0, 0.001, 0.0},     {-far_m, far_m, far_m, -far_m},
                                                   {1.234, -5.678, 1.234, 9.0}, {3.0, 3.0, -2.5, 2.999},
                                                   {7.0, 1.0, 6.999, -4.0},     {-0.001, -0.002, 0.0, 0.0}};
  std::int64_t id = 1;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    LineSegment s;
    s.id = id;
    id += (i == 2) ? 4'000'000 : 1 + static_cast<std::int64_t>(i);
    s.segment.start_m = {ends[i][0], ends[i][1]};
    s.segment.end_m = {ends[i][2], ends[i][3]};
    s.support_cells = (i == 1) ? static_cast<double>(std::int64_t{1} << 50) : 3.0 * static_cast<double>(i);
    s.observations = (i == 3) ? 0.0 : (i == 1) ? 1.0 : 40.0 * static_cast<double>(i);
    s.rms_error_m = FromQuanta(static_cast<std::int64_t>(i * 137), kRmsQuantumM);
    s.provenance = sources[i % sources.size()];
    snapshot.segments.push_back(s);
  }
  std::string error;
  std::optional<MapSnapshot> back = UnpackSnapshot(PackSnapshot(snapshot), &error);
  ASSERT_TRUE(back) << error;
  EXPECT_TRUE(SameMap(*back, snapshot));
  EXPECT_EQ(back->next_id, snapshot.next_id);
}

// A global wall's support (entities that saw it, error sd in cm) arrives exactly; an entity's map,
// which has none, pays one bit per message for it, and a global map's delta a few per wall.
TEST(MapPacking, GlobalWallSupportRoundTripsAndCostsAnEntityMapOneBit) {
  MapDelta entity;
  for (int i = 0; i < 40; ++i) {
    LineSegment s;
    s.id = i + 1;
    s.segment.start_m = {0.5 * i, 1.0};
    s.segment.end_m = {0.5 * i + 0.4, 1.0};
    s.support_cells = 12.0;
    s.observations = 30.0;
    s.provenance = {"ff1"};
    entity.added.push_back(s);
  }
  MapDelta global = entity;
  for (std::size_t i = 0; i < global.added.size(); ++i) {
    global.added[i].seen_by_entities = static_cast<std::uint32_t>(1 + i % 3);
    global.added[i].error_sd_m = FromQuanta(static_cast<std::int64_t>(3 + 7 * i), kErrorSdQuantumM);
  }
  global.added.back().error_sd_m = kMaxErrorSdM;
  global.added.front().seen_by_entities = 0;  // a plan-only piece
  global.added.front().error_sd_m = 0.0;
  std::string error;
  const std::string global_bytes = PackDelta(global);
  const std::optional<MapDelta> back = UnpackDelta(global_bytes, &error);
  ASSERT_TRUE(back) << error;
  ASSERT_EQ(back->added.size(), global.added.size());
  for (std::size_t i = 0; i < global.added.size(); ++i) {
    EXPECT_TRUE(SameSegment(back->added[i], global.added[i])) << "wall " << i;
    EXPECT_EQ(back->added[i].seen_by_entities, global.added[i].seen_by_entities);
    EXPECT_EQ(back->added[i].error_sd_m, global.added[i].error_sd_m);
  }
  const std::string entity_bytes = PackDelta(entity);
  const std::optional<MapDelta> entity_back = UnpackDelta(entity_bytes, &error);
  ASSERT_TRUE(entity_back) << error;
  EXPECT_EQ(entity_back->added.back().seen_by_entities, 0U);
  EXPECT_EQ(entity_back->added.back().error_sd_m, 0.0);
  EXPECT_GT(global_bytes.size(), entity_bytes.size());
  EXPECT_LE(global_bytes.size(), entity_bytes.size() + 2 * global.added.size());

  MapDelta off_quanta = global;
  off_quanta.added[1].error_sd_m = 0.125;  // not whole centimetres
  EXPECT_THROW(PackDelta(off_quanta), std::invalid_argument);
  MapDelta too_large = global;
  too_large.added[1].error_sd_m = kMaxErrorSdM + kErrorSdQuantumM;
  EXPECT_THROW(PackDelta(too_large), std::invalid_argument);
}

TEST(MapPacking, QuantiseSegmentClampsTheErrorSdToItsQuantaAndRange) {
  LineSegment s;
  s.error_sd_m = 0.1234;
  EXPECT_EQ(QuantiseSegment(s).error_sd_m, FromQuanta(12, kErrorSdQuantumM));
  s.error_sd_m = 1e9;
  EXPECT_EQ(QuantiseSegment(s).error_sd_m, kMaxErrorSdM);
  s.error_sd_m = -0.5;
  EXPECT_EQ(QuantiseSegment(s).error_sd_m, 0.0);
}

}  // namespace
}  // namespace pena::line_map
