// Map updates larger than the room in a packet (map_fragments.hpp): a big delta gets through a
// steady pose stream within a bound, a map larger than one frame crosses, lost pieces are resent,
// a restarted peer gets the update again, and the assembler copes with overlap, disorder and its
// memory limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "link_pair.hpp"
#include "pena/gateway/frame.hpp"
#include "pena/gateway/link_codec.hpp"
#include "pena/gateway/map_fragments.hpp"

namespace pena::gateway {
namespace {

using testing::Endpoint;
using testing::IdealLink;
using testing::LinkPair;

// `count` separate walls (3 m long, 1 m apart along x, 0.5 m apart along y): one delta that adds
// them all, about 7 bytes per wall in the gateway packing (this regular grid codes well).
MapChange BigDelta(const std::string& map_id, int count, line_map::LineMap* map) {
  std::vector<line_map::LineSegment> walls;
  for (int i = 0; i < count; ++i) {
    line_map::LineSegment wall;
    const double x = 4.0 * (i % 40);
    const double y = 0.5 * (i / 40);
    wall.segment.start_m = {x, y};
    wall.segment.end_m = {x + 3.0, y};
    wall.support_cells = 60;
    wall.observations = 10;
    walls.push_back(wall);
  }
  return MapChange{map_id, map->Integrate(walls, map_id), false};
}

std::size_t PackedBytes(const MapChange& change) {
  link::Item item;
  ToProto(change, 0, &item);
  return item.ByteSizeLong();
}

// Poses of 4 entities at 10 Hz each, stamped now: more than the packets can carry, so an
// unsent pose is always waiting (the stream that starved big deltas before fragments).
void OfferPoses(LinkPair& pair) {
  static const char* kEntities[] = {"ff1", "ff2", "ff3", "robot1"};
  for (const char* entity : kEntities) {
    pair.near.Offer(PoseUpdate{entity, {pair.now_s, 1.0, 0.5}, pair.now_s});
  }
}

std::uint64_t FarVersion(const LinkPair& pair, const std::string& map_id) {
  const auto found = pair.far.maps().find(map_id);
  return found == pair.far.maps().end() ? 0 : found->second.version();
}

EmulatedLinkOptions Radio9k6() {
  EmulatedLinkOptions radio = IdealLink();
  radio.rate_bit_s = 9600.0;
  radio.delay_s = 0.1;
  return radio;
}

// Default options without compression: the synthetic walls are regular and deflate well, and
// the bounds below count the bytes as packed.
LinkOptions Plain(std::uint64_t session) {
  LinkOptions options = Endpoint(session);
  options.compress = false;
  return options;
}

TEST(Fragments, LargeDeltaGetsThroughASteadyPoseStreamWithinABound) {
  LinkPair pair(Plain(1), Plain(2), Radio9k6(), Radio9k6());
  line_map::LineMap source;
  const MapChange delta = BigDelta("global", 200, &source);
  const std::size_t bytes = PackedBytes(delta);
  ASSERT_GT(bytes, 1500U) << "larger than a packet and than the token bucket";
  std::vector<double> pose_ages_s;
  double arrived_s = -1.0;
  const double offered_s = 5.0;
  bool offered = false;
  while (pair.now_s < 40.0) {
    if (!offered && pair.now_s >= offered_s) {
      pair.near.Offer(delta);
      offered = true;
    }
    if (std::fmod(pair.now_s + 1e-9, 0.1) < 0.01) OfferPoses(pair);
    const std::size_t before = pair.far.delivered().size();
    pair.Step(0.01);
    for (std::size_t i = before; i < pair.far.delivered().size(); ++i) {
      if (const auto* pose = std::get_if<PoseUpdate>(&pair.far.delivered()[i])) {
        pose_ages_s.push_back(pair.far.delivered_at_s()[i] - pose->stamp_s);
      }
    }
    if (arrived_s < 0.0 && FarVersion(pair, "global") == source.version()) arrived_s = pair.now_s;
  }
  // The bound: the delta's bytes at half the 8640 bit/s budget, plus 3 s of slack. (Without
  // fragments it never arrives while poses stream: it waited for a full bucket and an empty
  // packet, and a pose is always waiting.)
  const double bound_s = 8.0 * static_cast<double>(bytes) / 4320.0 + 3.0;
  ASSERT_GE(arrived_s, 0.0) << "the " << bytes << "-byte delta never arrived";
  EXPECT_LT(arrived_s - offered_s, bound_s);
  EXPECT_TRUE(line_map::SameMap(pair.far.maps().at("global").Snapshot(), source.Snapshot()));
  ASSERT_FALSE(pose_ages_s.empty());
  std::sort(pose_ages_s.begin(), pose_ages_s.end());
  const double p99 = pose_ages_s[pose_ages_s.size() * 99 / 100];
  EXPECT_LT(p99, 2.0);
  std::printf("[figures] %zu-byte delta behind 4 x 10 Hz poses at 9.6 kbit/s: arrived %.2f s "
              "after it was offered (bound %.1f s); pose age p99 %.2f s over %zu poses\n",
              bytes, arrived_s - offered_s, bound_s, p99, pose_ages_s.size());
}

TEST(Fragments, MapLargerThanAFrameCrossesThroughLoss) {
  EmulatedLinkOptions radio = Radio9k6();
  radio.rate_bit_s = 64000.0;
  radio.loss = 0.1;
  EmulatedLinkOptions back = radio;
  back.seed = 2;
  LinkOptions near = Endpoint(1);
  near.budget_bit_s = 57600.0;
  LinkPair pair(near, Endpoint(2), radio, back);
  line_map::LineMap source;
  const MapChange delta = BigDelta("global", 3000, &source);
  ASSERT_GT(PackedBytes(delta), FrameLimits{}.max_payload_bytes) << "needs more than one frame";
  pair.near.Offer(delta);
  // A reset snapshot of another map, just as large (the snapshot path).
  pair.near.Offer(MapChange{"ff1", source.Snapshot(), true});
  pair.RunUntil(60.0);
  EXPECT_EQ(FarVersion(pair, "global"), source.version());
  ASSERT_TRUE(pair.far.maps().count("ff1"));
  EXPECT_TRUE(line_map::SameMap(pair.far.maps().at("global").Snapshot(), source.Snapshot()));
  EXPECT_TRUE(line_map::SameMap(pair.far.maps().at("ff1").Snapshot(), source.Snapshot()));
  EXPECT_EQ(pair.near_session.scheduler().pending_deltas(), 0U);
  EXPECT_GT(pair.near_session.stats().sent[static_cast<std::size_t>(ItemClass::kMap)].resent, 0U)
      << "10 % loss: some pieces were resent";
  EXPECT_EQ(pair.far_session.stats().updates_reassembled, 2U);
  EXPECT_EQ(pair.far_session.stats().rejected_total(), 0U);
}

TEST(Fragments, RestartedPeerGetsTheWholeUpdateAgain) {
  InMemoryDomain near_domain;
  InMemoryDomain far_domain;
  InMemoryDomain fresh_domain;
  LinkSession near(Plain(1), near_domain);
  auto far = std::make_unique<LinkSession>(Plain(2), far_domain);
  InMemoryDomain* far_side = &far_domain;
  line_map::LineMap source;
  near_domain.Offer(BigDelta("global", 1000, &source));  // 12 kB: about 11 s at 8640 bit/s
  for (double now_s = 0.0; now_s < 60.0; now_s += 0.01) {
    if (now_s >= 5.0 && far_side == &far_domain) {  // restarts with part of the pieces held
      ASSERT_EQ(far_domain.maps().count("global"), 0U) << "the test needs the update in flight";
      far_side = &fresh_domain;
      far = std::make_unique<LinkSession>(Plain(3), fresh_domain);
    }
    for (const std::string& frame : near.Poll(now_s)) far->OnFrame(frame, now_s);
    for (const std::string& frame : far->Poll(now_s)) near.OnFrame(frame, now_s);
  }
  ASSERT_TRUE(fresh_domain.maps().count("global"));
  EXPECT_TRUE(line_map::SameMap(fresh_domain.maps().at("global").Snapshot(), source.Snapshot()));
}

link::Fragment Piece(std::uint64_t group, const std::string& whole, std::uint32_t offset,
                     std::uint32_t length) {
  link::Fragment fragment;
  fragment.set_group(group);
  fragment.set_total_bytes(static_cast<std::uint32_t>(whole.size()));
  fragment.set_offset(offset);
  fragment.set_data(whole.substr(offset, length));
  return fragment;
}

TEST(Fragments, AssemblerTakesOverlappingPiecesInAnyOrder) {
  std::string whole;
  for (int i = 0; i < 1000; ++i) whole.push_back(static_cast<char>(i * 7));
  FragmentAssembler assembler(1 << 20);
  EXPECT_FALSE(assembler.Add(Piece(5, whole, 600, 400)));
  EXPECT_FALSE(assembler.Add(Piece(5, whole, 100, 300)));
  EXPECT_FALSE(assembler.Add(Piece(5, whole, 250, 400)));  // overlaps both
  EXPECT_FALSE(assembler.Add(Piece(5, whole, 600, 400)));  // a duplicate
  EXPECT_EQ(assembler.buffered_bytes(), 900U);
  const std::optional<std::string> result = assembler.Add(Piece(5, whole, 0, 120));
  ASSERT_TRUE(result);
  EXPECT_EQ(*result, whole);
  EXPECT_EQ(assembler.buffered_bytes(), 0U);
  EXPECT_FALSE(assembler.Add(Piece(5, whole, 0, 1000))) << "a late resend of a completed group";
}

TEST(Fragments, AssemblerDropsTheOldestIncompleteUpdateBeyondItsLimit) {
  const std::string whole(1000, 'x');
  FragmentAssembler assembler(1500);
  EXPECT_FALSE(assembler.Add(Piece(1, whole, 0, 800)));
  EXPECT_FALSE(assembler.Add(Piece(2, whole, 0, 800)));  // 1600 held: group 1 goes
  EXPECT_EQ(assembler.dropped(), 1U);
  EXPECT_EQ(assembler.incomplete(), 1U);
  EXPECT_TRUE(assembler.Add(Piece(2, whole, 800, 200)));
  // At most `max_incomplete` updates: the oldest goes (a stream of stray pieces stays bounded).
  FragmentAssembler few(1 << 20, 2);
  for (std::uint64_t group = 1; group <= 1000; ++group) EXPECT_FALSE(few.Add(Piece(group, whole, 0, 10)));
  EXPECT_EQ(few.incomplete(), 2U);
  EXPECT_EQ(few.dropped(), 998U);
  EXPECT_TRUE(few.Add(Piece(1000, whole, 10, 990)));
}

TEST(Fragments, SessionRejectsMalformedFragmentsWithAMessage) {
  InMemoryDomain domain;
  LinkSession session(Endpoint(1), domain);
  struct Case {
    std::uint32_t total;
    std::uint32_t offset;
    std::string data;
    const char* expect;
  } cases[] = {
      {0, 0, "abc", "total_bytes 0"},
      {10, 8, "abc", "exceeds total_bytes"},
      {10, 0, "", "empty data"},
      {100u << 20, 0, "abc", "not in [1,"},
  };
  for (const Case& c : cases) {
    link::Envelope envelope;
    envelope.set_schema_version(kLinkSchemaVersion);
    link::Item* item = envelope.add_items();
    item->set_seq(1);
    item->mutable_fragment()->set_group(1);
    item->mutable_fragment()->set_total_bytes(c.total);
    item->mutable_fragment()->set_offset(c.offset);
    item->mutable_fragment()->set_data(c.data);
    const FrameResult result = session.OnFrame(EncodeFrame(envelope.SerializeAsString(), false), 1.0);
    EXPECT_EQ(result.status, FrameStatus::kBadPayload) << c.expect;
    EXPECT_NE(result.message.find(c.expect), std::string::npos) << result.message;
  }
  // Whole but not a map update: counted and dropped, not delivered.
  link::Envelope envelope;
  envelope.set_schema_version(kLinkSchemaVersion);
  link::Item pose;
  pose.mutable_pose()->set_entity("ff1");
  const std::string bytes = pose.SerializeAsString();
  *envelope.add_items()->mutable_fragment() = Piece(9, bytes, 0, static_cast<std::uint32_t>(bytes.size()));
  EXPECT_TRUE(session.OnFrame(EncodeFrame(envelope.SerializeAsString(), false), 2.0).ok());
  EXPECT_EQ(session.stats().reassembled_invalid, 1U);
  EXPECT_TRUE(domain.delivered().empty());
}

}  // namespace
}  // namespace pena::gateway
