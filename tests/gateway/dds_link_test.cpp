// The gateway's DDS side end to end, in one process on loopback DDS (deploy/dds/pena-loopback.xml):
// a "fusion" participant publishes poses, a global-map snapshot and deltas on domain A; a
// pena-gateway pair (DdsDomain "building" <-> LinkSession == in-memory link == LinkSession <->
// DdsDomain "command-post") carries them; a "coordinator" participant on domain B must see the
// same poses and build the same map. The snapshot and the first delta are larger than one link
// frame (16 KiB), so they cross in fragments.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>
#include <utility>

#include "dds_endpoints.hpp"
#include "from_dds.hpp"
#include "pena/gateway/dds_convert.hpp"
#include "pena/gateway/dds_domain.hpp"
#include "pena/gateway/frame.hpp"
#include "pena/gateway/link_codec.hpp"
#include "pena/gateway/link_session.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "service_test_support.hpp"
#include "to_dds.hpp"
#include "topics.hpp"

namespace pena::gateway {
namespace {

namespace topics = services::topics;
using services::testing::LoopbackDds;
using services::testing::TestDomain;

double WallS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// `count` separate walls starting at row `row0` (about 3 m long, 1 m apart along x, 0.5 m along
// y), their ends scattered by a few centimetres so that the gateway packing cannot code them as a
// regular grid (about 9-10 bytes each).
std::vector<line_map::LineSegment> Walls(int count, int row0) {
  std::vector<line_map::LineSegment> walls;
  for (int i = 0; i < count; ++i) {
    line_map::LineSegment wall;
    const int scatter = (i * 7919) % 1009;
    const double x = 4.0 * (i % 40) + 0.0003 * scatter;
    const double y = 0.5 * (row0 + i / 40) + 0.0001 * scatter;
    wall.segment.start_m = {x, y};
    wall.segment.end_m = {x + 3.0 - 0.0002 * scatter, y + 0.00007 * ((scatter * 31) % 1009)};
    wall.support_cells = 60;
    wall.observations = 10;
    walls.push_back(wall);
  }
  return walls;
}

std::size_t LinkBytes(const MapChange& change) {
  link::Item item;
  ToProto(change, 0, &item);
  return item.ByteSizeLong();
}

// What the coordinator's participant on domain B received.
struct Coordinator {
  std::mutex mutex;
  std::vector<pena_dds::EntityPose> poses;
  std::optional<line_map::LineMap> map;
  std::size_t snapshots = 0;
  std::size_t deltas = 0;
  std::size_t failed_applies = 0;

  std::uint64_t version() {
    std::lock_guard<std::mutex> lock(mutex);
    return map ? map->version() : 0;
  }
};

class GatewayPair {
 public:
  GatewayPair(int building_domain, int post_domain)
      : building_(Options(building_domain, "building")), post_(Options(post_domain, "command-post")),
        near_(Link(1), building_), far_(Link(2), post_) {}

  // One turn of both gateways' worker loops; frames cross at once (the link is not the subject).
  void Pump() {
    const double now_s = WallS();
    building_.set_clock(now_s);
    post_.set_clock(now_s);
    for (const std::string& frame : near_.Poll(now_s)) {
      ++frames_;
      max_frame_bytes_ = std::max(max_frame_bytes_, frame.size());
      EXPECT_TRUE(far_.OnFrame(frame, now_s).ok());
    }
    for (const std::string& frame : far_.Poll(now_s)) EXPECT_TRUE(near_.OnFrame(frame, now_s).ok());
  }

  DdsDomain& building() { return building_; }
  DdsDomain& post() { return post_; }
  LinkSession& near() { return near_; }
  LinkSession& far() { return far_; }
  std::size_t max_frame_bytes() const { return max_frame_bytes_; }

 private:
  static DdsDomainOptions Options(int domain, const std::string& role) {
    DdsDomainOptions options;
    options.dds = LoopbackDds(domain);
    options.name = "pena-gateway-test-" + role;
    options.role = *ParseDdsRole(role);
    options.snapshot_grace_s = 0.5;
    return options;
  }
  static LinkOptions Link(std::uint64_t session) {
    LinkOptions options;
    options.session = session;
    options.budget_bit_s = 256000.0;  // 32 kB/s: the 30 kB map crosses in about a second
    options.burst_bits = 8.0 * 4000.0;
    options.packet_bytes = 1400;
    return options;
  }

  DdsDomain building_;
  DdsDomain post_;
  LinkSession near_;
  LinkSession far_;
  std::size_t frames_ = 0;
  std::size_t max_frame_bytes_ = 0;
};

// Pumps the gateways until `done` or the timeout; false on timeout.
template <class Done>
bool PumpUntil(GatewayPair& pair, double timeout_s, Done done, const std::function<void()>& each = {}) {
  const double until_s = WallS() + timeout_s;
  while (WallS() < until_s) {
    pair.Pump();
    if (each) each();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(GatewayDds, PosesAndLargeMapsCrossBetweenTwoDomains) {
  const int domain_a = TestDomain(3);
  const int domain_b = TestDomain(4);
  ASSERT_NE(domain_a, domain_b);
  GatewayPair pair(domain_a, domain_b);

  // Fusion's stand-in on domain A.
  services::Participant fusion(LoopbackDds(domain_a), "test-fusion");
  services::Writer<pena_dds::EntityPosePubSubType> pose_writer(fusion, topics::kPose);
  services::Writer<pena_dds::GlobalMapSnapshotPubSubType> snapshot_writer(fusion, topics::kGlobalMapSnapshot);
  services::Writer<pena_dds::GlobalMapDeltaPubSubType> delta_writer(fusion, topics::kGlobalMapDelta);

  // The coordinator on domain B.
  Coordinator coordinator;
  services::Participant post(LoopbackDds(domain_b), "test-coordinator");
  services::Reader<pena_dds::EntityPosePubSubType> pose_reader(
      post, topics::kPose, [&](pena_dds::EntityPose&& sample, const services::SampleMeta&) {
        std::lock_guard<std::mutex> lock(coordinator.mutex);
        coordinator.poses.push_back(std::move(sample));
      });
  services::Reader<pena_dds::GlobalMapSnapshotPubSubType> snapshot_reader(
      post, topics::kGlobalMapSnapshot, [&](pena_dds::GlobalMapSnapshot&& sample, const services::SampleMeta&) {
        std::lock_guard<std::mutex> lock(coordinator.mutex);
        coordinator.map = line_map::LineMap::FromSnapshot(services::FromDds(sample));
        ++coordinator.snapshots;
      });
  services::Reader<pena_dds::GlobalMapDeltaPubSubType> delta_reader(
      post, topics::kGlobalMapDelta, [&](pena_dds::GlobalMapDelta&& sample, const services::SampleMeta&) {
        std::lock_guard<std::mutex> lock(coordinator.mutex);
        ++coordinator.deltas;
        if (!coordinator.map) coordinator.map.emplace();
        if (!coordinator.map->Apply(services::FromDds(sample)).ok()) ++coordinator.failed_applies;
      });

  // Discovery on both sides: the building gateway reads fusion's writers, the post gateway's
  // writers reach the coordinator's readers.
  ASSERT_TRUE(PumpUntil(pair, 20.0, [&] {
    return pose_writer.matched() > 0 && snapshot_writer.matched() > 0 && delta_writer.matched() > 0 &&
           pose_reader.matched() > 0 && snapshot_reader.matched() > 0 && delta_reader.matched() > 0;
  })) << "DDS endpoints did not match";
  ASSERT_TRUE(PumpUntil(pair, 10.0, [&] { return pair.near().peer_alive(WallS()); }));

  std::uint64_t pose_seq = 0;
  auto write_pose = [&] {
    PoseUpdate pose{"ff1", {1.25, -2.5, 0.5}, WallS()};
    pena_dds::EntityPose sample = PoseToDds(pose, ++pose_seq);
    pose_writer.Write(sample);
  };

  // A snapshot larger than a frame, as fusion publishes for a late joiner.
  line_map::LineMap source;
  source.Integrate(Walls(2040, 0), "global");
  const line_map::MapSnapshot snapshot = source.Snapshot();
  ASSERT_GT(LinkBytes(MapChange{"global", snapshot, true}), FrameLimits{}.max_payload_bytes);
  pena_dds::GlobalMapSnapshot snapshot_sample = services::ToDdsGlobalMapSnapshot(snapshot, "global", 1.0);
  ASSERT_TRUE(snapshot_writer.Write(snapshot_sample));
  ASSERT_TRUE(PumpUntil(pair, 30.0, [&] { return coordinator.version() == source.version(); }, write_pose))
      << "the snapshot did not reach the coordinator; building forwarded "
      << pair.building().stats().snapshots_forwarded << ", post published "
      << pair.post().stats().samples_published;

  // Then deltas: one larger than a frame, one small.
  const line_map::MapDelta big = source.Integrate(Walls(2040, 60), "global");
  ASSERT_GT(LinkBytes(MapChange{"global", big, false}), FrameLimits{}.max_payload_bytes);
  const line_map::MapDelta small = source.Integrate(Walls(3, 120), "global");
  // Then the fusion's support of those walls (who saw them, the estimated error sd), as a rebuild
  // publishes it: one entity alone, two, and a plan-only piece.
  line_map::MapDelta supported;
  supported.from_version = source.version();
  supported.to_version = source.version() + 1;
  supported.changed = small.added;
  const std::vector<std::pair<std::uint32_t, double>> support = {{1, 0.23}, {2, 0.07}, {0, 0.0}};
  for (std::size_t i = 0; i < support.size(); ++i) {
    supported.changed[i].seen_by_entities = support[i].first;
    supported.changed[i].error_sd_m = line_map::Quantise(support[i].second, line_map::kErrorSdQuantumM);
  }
  ASSERT_TRUE(source.Apply(supported).ok());
  for (const line_map::MapDelta* delta : {&big, &small, &std::as_const(supported)}) {
    pena_dds::GlobalMapDelta sample = services::ToDdsGlobalMapDelta(*delta, "global", 2.0);
    ASSERT_TRUE(delta_writer.Write(sample));
  }
  ASSERT_TRUE(PumpUntil(pair, 30.0, [&] { return coordinator.version() == source.version(); }, write_pose))
      << "the deltas did not reach the coordinator (version " << coordinator.version() << " of "
      << source.version() << ")";
  PumpUntil(pair, 1.0, [] { return false; }, write_pose);  // a few more poses

  std::lock_guard<std::mutex> lock(coordinator.mutex);
  EXPECT_TRUE(line_map::SameMap(coordinator.map->Snapshot(), source.Snapshot()));
  const std::vector<line_map::LineSegment> arrived = coordinator.map->segments();
  for (std::size_t i = 0; i < support.size(); ++i) {
    const std::int64_t id = supported.changed[i].id;
    const auto wall = std::find_if(arrived.begin(), arrived.end(),
                                   [id](const line_map::LineSegment& s) { return s.id == id; });
    ASSERT_NE(wall, arrived.end()) << "wall " << id;
    EXPECT_EQ(wall->seen_by_entities, support[i].first) << "wall " << id;
    EXPECT_NEAR(wall->error_sd_m, support[i].second, 1e-12) << "wall " << id;
  }
  EXPECT_EQ(coordinator.snapshots, 1U);
  EXPECT_EQ(coordinator.deltas, 3U);
  EXPECT_EQ(coordinator.failed_applies, 0U);
  EXPECT_LE(pair.max_frame_bytes(), 1400U + kFrameHeaderBytes + kFrameTrailerBytes);
  EXPECT_GE(pair.far().stats().updates_reassembled, 2U);
  ASSERT_FALSE(coordinator.poses.empty());
  const pena_dds::EntityPose& last = coordinator.poses.back();
  EXPECT_EQ(last.entity_id().to_string(), "ff1");
  EXPECT_NEAR(last.world_from_body().x_m(), 1.25, 0.01);
  EXPECT_NEAR(last.world_from_body().y_m(), -2.5, 0.01);
  // Nothing echoed: the building gateway read only fusion's samples, not its own.
  EXPECT_EQ(pair.building().stats().samples_published, 0U);
  std::printf("[figures] DDS A -> gateway pair -> DDS B: %zu poses, snapshot %zu and deltas %zu "
              "link bytes, %llu updates reassembled, largest frame %zu bytes\n",
              coordinator.poses.size(), LinkBytes(MapChange{"global", snapshot, true}),
              LinkBytes(MapChange{"global", big, false}),
              static_cast<unsigned long long>(pair.far().stats().updates_reassembled),
              pair.max_frame_bytes());
}

}  // namespace
}  // namespace pena::gateway
