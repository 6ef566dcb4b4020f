// The scheduler's policy: priorities, stale poses replaced, reliable classes resent until
// confirmed, the bit budget kept, and resynchronisation after an outage without resending.
#include <gtest/gtest.h>

#include "link_pair.hpp"
#include "pena/gateway/link_codec.hpp"
#include "pena/gateway/link_scheduler.hpp"
#include "pena/gateway/synthetic_team.hpp"

namespace pena::gateway {
namespace {

using testing::Endpoint;
using testing::IdealLink;
using testing::LinkPair;

MapChange FirstDelta(const std::string& map_id) {
  line_map::LineMap map;
  line_map::LineSegment wall;
  wall.segment.end_m = {3.0, 0.0};
  wall.support_cells = 60;
  wall.observations = 100;
  return MapChange{map_id, map.Integrate({wall}, map_id), false};
}

link::Item::BodyCase Body(const link::Envelope& envelope, int i) { return envelope.items(i).body_case(); }

TEST(Scheduler, SendsAlarmsThenPosesThenCorrectionsThenMaps) {
  LinkScheduler scheduler;
  scheduler.Offer(FirstDelta("ff1"));
  scheduler.Offer(Correction{"ff1", {1.0, 2.0, 0.1}, 1, 5.0});
  scheduler.Offer(PoseUpdate{"ff1", {1.0, 1.0, 0.0}, 5.0});
  scheduler.Offer(Annotation{true, "ff1", 1, 1.0, 1.0, 5.0, "down"});
  link::Envelope envelope;
  scheduler.Fill(&envelope, 1000, false, 5.0);
  ASSERT_EQ(envelope.items_size(), 4);
  EXPECT_EQ(Body(envelope, 0), link::Item::kAnnotation);
  EXPECT_EQ(Body(envelope, 1), link::Item::kPose);
  EXPECT_EQ(Body(envelope, 2), link::Item::kCorrection);
  EXPECT_EQ(Body(envelope, 3), link::Item::kMap);
  // With room for only a little, the alarm goes first and the rest waits.
  link::Envelope small;
  const Selection selection = scheduler.Fill(&small, 40, false, 5.0);
  ASSERT_EQ(small.items_size(), 1);
  EXPECT_EQ(Body(small, 0), link::Item::kAnnotation);
  EXPECT_TRUE(selection.full);
}

TEST(Scheduler, ReplacesStalePosesInsteadOfQueueingThem) {
  LinkScheduler scheduler;
  for (int i = 0; i < 10; ++i) scheduler.Offer(PoseUpdate{"ff1", {double(i), 0.0, 0.0}, double(i)});
  scheduler.Offer(PoseUpdate{"ff2", {0.0, 0.0, 0.0}, 3.0});
  scheduler.Offer(PoseUpdate{"ff1", {99.0, 0.0, 0.0}, 2.0});  // older than the one held: ignored
  link::Envelope envelope;
  envelope.set_base_stamp_ms(10000);
  const Selection selection = scheduler.Fill(&envelope, 1000, false, 10.0);
  ASSERT_EQ(envelope.items_size(), 2);
  EXPECT_EQ(envelope.items(0).pose().entity(), "ff2");  // older stamp first
  EXPECT_EQ(envelope.items(1).pose().x_cm(), 900);      // ff1's newest
  EXPECT_EQ(scheduler.replaced_poses(), 9U);
  LinkStats stats;
  scheduler.Commit(selection, 10.0, &stats);
  link::Envelope again;
  scheduler.Fill(&again, 1000, false, 20.0);
  EXPECT_EQ(again.items_size(), 0) << "a sent pose is never resent";
}

TEST(Scheduler, ResendsMapDeltasUntilThePeerHoldsTheirVersion) {
  SchedulerOptions options;
  options.retransmit_timeout_s = 2.0;
  LinkScheduler scheduler(options);
  scheduler.Offer(FirstDelta("ff1"));
  LinkStats stats;
  auto send = [&](double now_s) {
    link::Envelope envelope;
    const Selection selection = scheduler.Fill(&envelope, 1000, false, now_s);
    scheduler.Commit(selection, now_s, &stats);
    return envelope.items_size();
  };
  EXPECT_EQ(send(0.0), 1);
  EXPECT_EQ(send(1.0), 0);  // not due yet
  EXPECT_EQ(send(2.0), 1);  // resent after the timeout
  EXPECT_EQ(send(5.0), 0);  // the timeout doubled to 4 s
  EXPECT_EQ(send(6.0), 1);
  EXPECT_EQ(stats.sent[static_cast<std::size_t>(ItemClass::kMap)].resent, 2U);
  link::ResyncSummary summary;
  link::MapVersion* version = summary.add_maps();
  version->set_map_id("ff1");
  version->set_version(1);
  scheduler.OnPeerSummary(summary, &stats);
  EXPECT_EQ(scheduler.pending_deltas(), 0U);
  EXPECT_EQ(send(100.0), 0);
}

TEST(Scheduler, ResendsAnnotationsUntilAcknowledged) {
  LinkScheduler scheduler;
  scheduler.Offer(Annotation{false, "ff1", 1, 0.0, 0.0, 0.0, "stairs blocked"});
  scheduler.Offer(Annotation{true, "ff2", 1, 0.0, 0.0, 0.0, "down"});
  LinkStats stats;
  link::Envelope envelope;
  scheduler.Commit(scheduler.Fill(&envelope, 1000, false, 0.0), 0.0, &stats);
  ASSERT_EQ(envelope.items_size(), 2);
  link::Ack ack;
  ack.add_selective(envelope.items(1).seq());  // only the second arrived
  scheduler.OnAck(ack);
  EXPECT_EQ(scheduler.pending_annotations(), 1U);
  link::Envelope later;
  scheduler.Fill(&later, 1000, false, 10.0);
  ASSERT_EQ(later.items_size(), 1);
  EXPECT_EQ(later.items(0).annotation().text(), "stairs blocked");
  ack.set_cumulative(later.items(0).seq());
  scheduler.OnAck(ack);
  EXPECT_EQ(scheduler.pending_annotations(), 0U);
}

TEST(Scheduler, KeepsTheBitBudgetOverTime) {
  LinkOptions near = Endpoint(1);
  near.budget_bit_s = 4800.0;
  near.burst_bits = 8.0 * 1200.0;
  LinkPair pair(near, Endpoint(2), IdealLink(), IdealLink());
  SyntheticTeamOptions team_options;
  team_options.entities = 6;
  team_options.pose_rate_hz = 10.0;
  team_options.map_period_s = 0.5;  // far more than 4.8 kbit/s can carry
  SyntheticTeam team(team_options);
  const double duration_s = 120.0;
  while (pair.now_s < duration_s) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
  }
  const double sent_bits = 8.0 * static_cast<double>(pair.near_session.stats().wire_bytes_sent);
  EXPECT_LE(sent_bits, near.budget_bit_s * duration_s + near.burst_bits);
  EXPECT_GE(sent_bits, 0.9 * near.budget_bit_s * duration_s) << "the budget should be used";
  // Over every 10 s window, too (no burst beyond the bucket).
  std::vector<double> bits_per_window(12, 0.0);
  for (const auto& [t, frame] : pair.sent_forward) {
    bits_per_window[std::min<std::size_t>(11, static_cast<std::size_t>(t / 10.0))] += 8.0 * double(frame.size() + 28);
  }
  for (double bits : bits_per_window) EXPECT_LE(bits, near.budget_bit_s * 10.0 + near.burst_bits);
  EXPECT_GT(pair.near_session.scheduler().pending_deltas(), 0U) << "the load exceeds the budget";
}

// Map versions the far side holds, by map id.
std::map<std::string, std::uint64_t> FarVersions(const LinkPair& pair) {
  std::map<std::string, std::uint64_t> versions;
  for (const auto& [map_id, map] : pair.far.maps()) versions[map_id] = map.version();
  return versions;
}

TEST(Scheduler, ResynchronisesAfterAnOutageWithoutResendingWhatTheFarSideHas) {
  EmulatedLinkOptions link = IdealLink();
  link.rate_bit_s = 9600.0;
  link.outages = {{30.0, 60.0}};
  LinkOptions near = Endpoint(1);
  LinkPair pair(near, Endpoint(2), link, link);
  SyntheticTeamOptions team_options;
  team_options.map_until_s = 80.0;
  SyntheticTeam team(team_options);
  std::map<std::string, std::uint64_t> held_at_outage;
  while (pair.now_s < 180.0) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
    if (held_at_outage.empty() && pair.now_s >= 30.0) held_at_outage = FarVersions(pair);
  }
  ASSERT_FALSE(held_at_outage.empty());
  EXPECT_GE(pair.near_session.stats().resyncs, 1U);
  EXPECT_GE(pair.far_session.stats().resyncs, 1U);
  // After the outage, no frame carries a delta the far side already held before it.
  std::size_t deltas_after = 0;
  for (const auto& [t, frame] : pair.sent_forward) {
    if (t < 60.0) continue;
    link::Envelope envelope;
    ASSERT_TRUE(envelope.ParseFromString(DecodeFrame(frame).payload));
    for (const link::Item& item : envelope.items()) {
      if (!item.has_map()) continue;
      ++deltas_after;
      EXPECT_GT(item.map().to_version(), held_at_outage[item.map().map_id()])
          << item.map().map_id() << " resent at t=" << t;
    }
  }
  EXPECT_GT(deltas_after, 0U);
  for (const auto& [map_id, map] : team.maps()) {
    ASSERT_TRUE(pair.far.maps().count(map_id)) << map_id;
    EXPECT_TRUE(line_map::SameMap(pair.far.maps().at(map_id).Snapshot(), map.Snapshot())) << map_id;
  }
}

TEST(Scheduler, SendsASnapshotWhenThePeerLostItsMap) {
  InMemoryDomain near_domain;
  InMemoryDomain far_domain;
  InMemoryDomain fresh_domain;
  LinkSession near(Endpoint(1), near_domain);
  auto far = std::make_unique<LinkSession>(Endpoint(2), far_domain);
  SyntheticTeamOptions team_options;
  team_options.map_until_s = 20.0;
  SyntheticTeam team(team_options);
  InMemoryDomain* far_side = &far_domain;
  for (double now_s = 0.0; now_s < 80.0; now_s += 0.01) {
    if (now_s >= 40.0 && far_side == &far_domain) {  // the far gateway restarts with nothing
      far_side = &fresh_domain;
      far = std::make_unique<LinkSession>(Endpoint(3), fresh_domain);
    }
    for (DomainItem& item : team.Advance(now_s)) near_domain.Offer(std::move(item));
    for (const std::string& frame : near.Poll(now_s)) far->OnFrame(frame, now_s);
    for (const std::string& frame : far->Poll(now_s)) near.OnFrame(frame, now_s);
  }
  EXPECT_GE(near.stats().snapshots_queued, 1U);
  for (const auto& [map_id, map] : team.maps()) {
    ASSERT_TRUE(fresh_domain.maps().count(map_id)) << map_id;
    EXPECT_TRUE(line_map::SameMap(fresh_domain.maps().at(map_id).Snapshot(), map.Snapshot())) << map_id;
  }
}

}  // namespace
}  // namespace pena::gateway
