// The DDS helpers on loopback: typed writer/reader pairs from the XML QoS profiles, keyed
// instances, and transient-local delivery to a late joiner.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "dds_endpoints.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "service_test_support.hpp"
#include "to_dds.hpp"
#include "work_queue.hpp"

namespace pena::services {
namespace {

using std::chrono::milliseconds;

template <class Predicate>
bool WaitUntil(Predicate done, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(timeout_s));
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(milliseconds(10));
  }
  return true;
}

// 20 entities: more than Fast DDS's default of 10 instances, which pena-qos.xml raises to 256.
TEST(DdsEndpoints, PosesFromManyEntitiesArriveAsOneInstanceEach) {
  const DdsOptions options = testing::LoopbackDds(testing::TestDomain(1));
  Participant sender(options, "sender");
  Participant receiver(options, "receiver");
  WorkQueue<pena_dds::EntityPose> received;
  Reader<pena_dds::EntityPosePubSubType> reader(
      receiver, topics::kPose,
      [&](pena_dds::EntityPose&& pose, const SampleMeta&) { received.Push(std::move(pose)); });
  Writer<pena_dds::EntityPosePubSubType> writer(sender, topics::kPose);
  ASSERT_TRUE(WaitUntil([&] { return writer.matched() > 0; }, 10.0));
  std::set<std::string> seen;
  for (int i = 0; i < 200 && seen.size() < 20; ++i) {
    for (int e = 0; e < 20; ++e) {
      pena_dds::EntityPose pose;
      pose.entity_id("ff" + std::to_string(e));
      pose.schema_version(pena_dds::SCHEMA_VERSION);
      pose.seq(static_cast<std::uint64_t>(i + 1));
      writer.Write(pose);
    }
    while (auto pose = received.PopFor(milliseconds(20))) seen.insert(pose->entity_id().to_string());
  }
  EXPECT_EQ(seen.size(), 20u);
}

TEST(DdsEndpoints, LateJoinerGetsTheGlobalSnapshot) {
  const DdsOptions options = testing::LoopbackDds(testing::TestDomain(2));
  Participant fusion(options, "fusion");
  Writer<pena_dds::GlobalMapSnapshotPubSubType> writer(fusion, topics::kGlobalMapSnapshot);
  line_map::LineMap map;
  line_map::LineSegment wall;
  wall.segment = {{0.0, 0.0}, {4.0, 0.0}};
  map.Integrate({wall}, "apriori");
  pena_dds::GlobalMapSnapshot snapshot = ToDdsGlobalMapSnapshot(map.Snapshot(), kGlobalMapId, 1.0);
  ASSERT_TRUE(writer.Write(snapshot));
  // The reader is created only now: transient-local durability must still deliver it.
  Participant late(options, "late");
  WorkQueue<pena_dds::GlobalMapSnapshot> received;
  Reader<pena_dds::GlobalMapSnapshotPubSubType> reader(
      late, topics::kGlobalMapSnapshot,
      [&](pena_dds::GlobalMapSnapshot&& s, const SampleMeta&) { received.Push(std::move(s)); });
  const auto got = received.PopFor(std::chrono::seconds(10));
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->version(), 1u);
  ASSERT_EQ(got->segments().size(), 1u);
  EXPECT_EQ(got->segments()[0].end_x_mm(), 4000);
}

TEST(DdsEndpoints, UnknownParticipantProfileIsADdsErrorNamingIt) {
  DdsOptions options = testing::LoopbackDds(testing::TestDomain(3));
  options.participant_profile = "no_such_profile";
  try {
    Participant participant(options, "broken");
    FAIL() << "no exception";
  } catch (const DdsError& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_profile"), std::string::npos);
  }
  options.participant_profile = "pena_loopback";
  options.profiles_files = {};
  EXPECT_THROW(Participant(options, "empty"), DdsError);
  options.profiles_files = {"/nonexistent/profiles.xml"};
  EXPECT_THROW(Participant(options, "missing"), DdsError);
}

}  // namespace
}  // namespace pena::services
