// LockstepOrder (services/fusion/lockstep_order.hpp): pena-fusion --lockstep handles deltas and
// reference scans in one mission-time order, whatever order DDS delivered them in.
#include "lockstep_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace pena::services {
namespace {

constexpr std::int64_t kSecondNs = 1'000'000'000;

std::vector<std::uint64_t> Drain(LockstepOrder& order, std::int64_t now_ns,
                                 std::vector<LockstepRelease>* releases = nullptr) {
  std::vector<std::uint64_t> tokens;
  while (std::optional<LockstepRelease> release = order.Next(now_ns)) {
    tokens.push_back(release->token);
    if (releases != nullptr) releases->push_back(*release);
  }
  return tokens;
}

// One entity's samples as pena-entity sends them: per scan at stamp t the delta (if the map
// changed), the pose, and every other scan a reference scan; a status at the end.
struct Stream {
  std::vector<std::function<void(LockstepOrder&)>> events;
};

// Two entities whose stamps coincide in part (simulated entities scan together), sent the way
// pena-entity sends them (delta, reference scan, pose; a correction's delta after the answer).
// Tokens say the expected order: (stamp, entity id, the entity's own order).
Stream TwoEntities() {
  Stream stream;
  auto& e = stream.events;
  // Each entity's status (its kind): published first, but on its own topic.
  e.push_back([](LockstepOrder& o) { o.StatusHeard("A"); });
  e.push_back([](LockstepOrder& o) { o.StatusHeard("B"); });
  // A: stamps 1, 2, 3.
  e.push_back([](LockstepOrder& o) { o.AddDelta("A", 1.0, 0, 1, 0, 1, 0); });
  e.push_back([](LockstepOrder& o) { o.AddScan("A", 1.0, 1, 1, 2, 0); });
  e.push_back([](LockstepOrder& o) { o.Progress("A", 1.0, 1, 1); });
  e.push_back([](LockstepOrder& o) { o.AddDelta("A", 1.0, 1, 2, 1, 3, 0); });  // a correction's
  e.push_back([](LockstepOrder& o) { o.AddScan("A", 2.0, 2, 2, 7, 0); });
  e.push_back([](LockstepOrder& o) { o.Progress("A", 2.0, 2, 2); });
  e.push_back([](LockstepOrder& o) { o.AddDelta("A", 3.0, 2, 3, 2, 8, 0); });
  e.push_back([](LockstepOrder& o) { o.Progress("A", 3.0, 3, 2); });
  e.push_back([](LockstepOrder& o) { o.Finished("A", 3, 2); });
  // B: stamps 1, 1.5, 3.
  e.push_back([](LockstepOrder& o) { o.AddDelta("B", 1.0, 0, 1, 0, 4, 0); });
  e.push_back([](LockstepOrder& o) { o.AddScan("B", 1.0, 1, 1, 5, 0); });
  e.push_back([](LockstepOrder& o) { o.AddDelta("B", 1.5, 1, 2, 1, 6, 0); });
  e.push_back([](LockstepOrder& o) { o.Progress("B", 1.5, 2, 1); });
  e.push_back([](LockstepOrder& o) { o.AddDelta("B", 3.0, 2, 3, 1, 9, 0); });
  e.push_back([](LockstepOrder& o) { o.AddScan("B", 3.0, 3, 2, 10, 0); });
  e.push_back([](LockstepOrder& o) { o.Finished("B", 3, 2); });
  return stream;
}

TEST(LockstepOrder, ReleasesInMissionOrderWhateverTheArrivalOrder) {
  const Stream stream = TwoEntities();
  const std::vector<std::uint64_t> expected{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::size_t> arrival(stream.events.size());
    for (std::size_t i = 0; i < arrival.size(); ++i) arrival[i] = i;
    if (trial > 0) std::shuffle(arrival.begin(), arrival.end(), random);
    LockstepOrder order({{"A", "B"}, 10.0});
    std::vector<std::uint64_t> released;
    for (std::size_t index : arrival) {
      stream.events[index](order);
      for (std::uint64_t token : Drain(order, 0)) released.push_back(token);
    }
    ASSERT_EQ(released, expected) << "trial " << trial;
    EXPECT_EQ(order.held(), 0u);
    EXPECT_EQ(order.forced(), 0);
  }
}

// The correction filter and the placement need the entity's kind and start from its status,
// which travels on its own topic: a scan that overtook it waits (else one run matches it as a
// robot and the next as a person), and a stall still lets it out if the status never comes.
TEST(LockstepOrder, AnEntitysItemsWaitForItsStatus) {
  LockstepOrder order({{}, 3.0});
  order.AddScan("A", 1.0, 0, 1, 1, 0);
  order.AddDelta("A", 1.0, 0, 1, 1, 2, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.StatusHeard("A");
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{1, 2}));
  order.Finished("A", 1, 1);
  order.AddScan("B", 2.0, 0, 1, 3, 0);
  EXPECT_TRUE(Drain(order, 2 * kSecondNs).empty());
  std::vector<LockstepRelease> releases;
  EXPECT_EQ(Drain(order, 4 * kSecondNs, &releases), (std::vector<std::uint64_t>{3}));
  ASSERT_EQ(releases.size(), 1u);
  EXPECT_TRUE(releases[0].forced);
  // ... and its status is not waited for again.
  order.AddScan("B", 3.0, 0, 2, 4, 4 * kSecondNs);
  EXPECT_EQ(Drain(order, 4 * kSecondNs), (std::vector<std::uint64_t>{4}));
}

TEST(LockstepOrder, AScanWaitsForTheDeltasItsMapHolds) {
  LockstepOrder order({{}, 10.0});
  order.StatusHeard("A");
  order.AddScan("A", 1.0, 2, 1, 10, 0);
  order.AddDelta("A", 0.5, 0, 1, 0, 11, 0);
  // The delta to version 2 is still on its way: only the first delta may go.
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{11}));
  order.AddDelta("A", 1.0, 1, 2, 0, 12, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{12, 10}));
}

TEST(LockstepOrder, ADeltaWaitsForTheScansSentBeforeIt) {
  LockstepOrder order({{}, 10.0});
  order.StatusHeard("A");
  // The delta after scan 1 overtook it (another topic): it waits for the scan.
  order.AddDelta("A", 2.0, 0, 1, 1, 1, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.AddScan("A", 1.0, 0, 1, 2, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{2, 1}));
  // And a scan waits for the scans before it.
  order.AddScan("A", 3.0, 1, 3, 3, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.AddScan("A", 2.5, 1, 2, 4, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{4, 3}));
}

TEST(LockstepOrder, AnEntityBehindHoldsTheOthersUntilItPassesTheStamp) {
  LockstepOrder order({{}, 10.0});
  for (const char* id : {"A", "B"}) order.StatusHeard(id);
  order.Progress("B", 0.5, 0, 0);
  order.AddScan("A", 1.0, 0, 1, 1, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  // B's pose at 1.0 with a version whose delta has not come: not yet.
  order.Progress("B", 1.0, 1, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.AddDelta("B", 0.8, 0, 1, 0, 2, 0);
  // B's delta at 0.8 comes first, then A's scan (B reached 1.0 and A < B at equal stamps).
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{2, 1}));
}

TEST(LockstepOrder, AtEqualStampsTheLaterIdWaitsUntilTheEarlierMovedOn) {
  LockstepOrder order({{}, 10.0});
  for (const char* id : {"A", "B"}) order.StatusHeard(id);
  order.AddScan("B", 1.0, 0, 1, 1, 0);
  order.AddScan("A", 1.0, 0, 1, 2, 0);
  // A's scan goes first; B's waits until A is past 1.0 (a correction delta of A at 1.0 may come).
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{2}));
  order.AddDelta("A", 1.0, 0, 1, 1, 3, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{3}));
  order.Progress("A", 1.25, 1, 1);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{1}));
}

TEST(LockstepOrder, AnExpectedEntityIsWaitedForUntilItIsHeard) {
  LockstepOrder order({{"A", "B"}, 10.0});
  for (const char* id : {"A", "B"}) order.StatusHeard(id);
  order.AddScan("A", 1.0, 0, 1, 1, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.Join("B", 0, true);
  order.Progress("B", 2.0, 0, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{1}));
}

TEST(LockstepOrder, AStalledEntityIsPassedOverAfterStallAndWaitedForAgainOnceItCatchesUp) {
  LockstepOrder order({{}, 3.0});
  for (const char* id : {"A", "B"}) order.StatusHeard(id);
  order.Progress("B", 0.5, 0, 0);
  order.AddScan("A", 1.0, 0, 1, 1, 0);
  EXPECT_TRUE(Drain(order, 2 * kSecondNs).empty());
  std::vector<LockstepRelease> releases;
  EXPECT_EQ(Drain(order, 4 * kSecondNs, &releases), (std::vector<std::uint64_t>{1}));
  ASSERT_EQ(releases.size(), 1u);
  EXPECT_TRUE(releases[0].forced);
  EXPECT_EQ(releases[0].waited_for, "B");
  EXPECT_EQ(order.forced(), 1);
  // B is passed over now: A's next scan goes at once.
  order.AddScan("A", 2.0, 0, 2, 2, 4 * kSecondNs);
  EXPECT_EQ(Drain(order, 4 * kSecondNs), (std::vector<std::uint64_t>{2}));
  // B catches up past what was released: it is waited for again.
  order.Progress("B", 2.5, 0, 0);
  order.AddScan("A", 3.0, 0, 3, 3, 5 * kSecondNs);
  EXPECT_TRUE(Drain(order, 5 * kSecondNs).empty());
  order.Progress("B", 3.5, 0, 0);
  EXPECT_EQ(Drain(order, 5 * kSecondNs), (std::vector<std::uint64_t>{3}));
}

TEST(LockstepOrder, ALostDeltaIsForcedOutAfterStallSoTheStoreSeesTheGap) {
  LockstepOrder order({{}, 3.0});
  order.StatusHeard("A");
  order.AddDelta("A", 1.0, 1, 2, 0, 1, 0);  // 0 -> 1 never comes
  EXPECT_TRUE(Drain(order, kSecondNs).empty());
  EXPECT_EQ(Drain(order, 4 * kSecondNs), (std::vector<std::uint64_t>{1}));
  order.AddDelta("A", 2.0, 2, 3, 0, 2, 4 * kSecondNs);
  EXPECT_EQ(Drain(order, 4 * kSecondNs), (std::vector<std::uint64_t>{2}));
}

TEST(LockstepOrder, ADroppedOrFinishedEntityNoLongerHoldsTheOthers) {
  LockstepOrder order({{}, 10.0});
  for (const char* id : {"A", "B", "C"}) order.StatusHeard(id);
  order.Progress("B", 0.5, 0, 0);
  order.Progress("C", 0.5, 1, 0);
  order.AddScan("A", 1.0, 0, 1, 1, 0);
  order.Drop("B");
  EXPECT_TRUE(Drain(order, 0).empty());
  // C finished at version 1 but its delta is still on its way.
  order.Finished("C", 1, 0);
  EXPECT_TRUE(Drain(order, 0).empty());
  order.AddDelta("C", 0.5, 0, 1, 0, 2, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{2, 1}));
}

TEST(LockstepOrder, ADeltaReceivedTwiceIsReleasedTwiceNotLost) {
  LockstepOrder order({{}, 10.0});
  order.StatusHeard("A");
  order.AddDelta("A", 1.0, 0, 1, 0, 1, 0);
  order.AddDelta("A", 1.0, 0, 1, 0, 2, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{1, 2}));
}

TEST(LockstepOrder, AfterARestartDeltasTheStoreHoldsPassAtOnce) {
  LockstepOrder order({{}, 10.0});
  order.Join("A", 5, false);
  order.StatusHeard("A");
  // Durable history sent again (4 scans had gone before the first sample heard), then new.
  order.AddDelta("A", 1.0, 2, 3, 4, 1, 0);
  order.AddDelta("A", 9.0, 5, 6, 4, 2, 0);
  EXPECT_EQ(Drain(order, 0), (std::vector<std::uint64_t>{1, 2}));
}

TEST(LockstepOrder, OptionsAreValidated) {
  EXPECT_THROW(LockstepOrder({{}, 0.0}), std::invalid_argument);
  EXPECT_THROW(LockstepOrder({{}, -1.0}), std::invalid_argument);
  EXPECT_THROW(LockstepOrder({{"ff1", ""}, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::services
