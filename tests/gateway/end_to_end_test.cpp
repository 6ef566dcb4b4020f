// A team's picture through an emulated 9.6 kbit/s radio link with delay, loss and a 30 s outage
// (simulated time), sealed as deployed (docs/security.md): no map delta is lost, the far side's
// maps equal the near side's, every alarm arrives once, and poses stay fresh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "link_pair.hpp"
#include "team_checks.hpp"
#include "pena/gateway/link_crypto.hpp"
#include "pena/gateway/synthetic_team.hpp"

namespace pena::gateway {
namespace {

using testing::Endpoint;
using testing::LinkPair;
using testing::MapsEqual;
using testing::Percentile;

TEST(EndToEnd, NoMapDeltaLostThroughA30SecondOutageAt9600Bits) {
  EmulatedLinkOptions radio;
  radio.rate_bit_s = 9600.0;
  radio.delay_s = 0.2;
  radio.loss = 0.05;
  radio.outages = {{100.0, 130.0}};
  EmulatedLinkOptions back = radio;
  back.seed = 2;
  LinkOptions near = Endpoint(1);
  LinkOptions far = Endpoint(2);
  near.key = far.key = GenerateLinkKey();
  LinkPair pair(near, far, radio, back);
  SyntheticTeamOptions team_options;  // 4 entities, 2 Hz poses, walls every 2 s, alarms
  team_options.map_until_s = 200.0;
  SyntheticTeam team(team_options);
  double converged_s = -1.0;
  // The team acts for 320 s; then 10 s more let the link drain, so an alarm raised just before
  // the end whose frame is lost gets its resend (3 s timeout) like any other.
  while (pair.now_s < 330.0) {
    if (pair.now_s < 320.0) {
      for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    }
    pair.Step(0.01);
    if (std::fmod(pair.now_s, 0.5) > 0.01) continue;  // compare maps twice a second
    const bool equal = MapsEqual(team, pair.far);
    if (pair.now_s > team.last_map_change_s() && equal && converged_s < 0.0) converged_s = pair.now_s;
    if (!equal) converged_s = -1.0;
  }
  // Maps: every delta arrived, in order, and the far maps are the near maps bit for bit.
  EXPECT_TRUE(MapsEqual(team, pair.far));
  EXPECT_EQ(pair.far.failed_applies(), 0U);
  EXPECT_EQ(pair.near_session.scheduler().pending_deltas(), 0U);
  ASSERT_GE(converged_s, 0.0);
  const double convergence_s = converged_s - team.last_map_change_s();
  EXPECT_LT(convergence_s, 60.0);
  // Alarms: each exactly once. Poses: age at delivery outside the outage.
  std::set<std::uint64_t> alarms;
  std::size_t alarm_deliveries = 0;
  std::vector<double> pose_ages_s;
  for (std::size_t i = 0; i < pair.far.delivered().size(); ++i) {
    const DomainItem& item = pair.far.delivered()[i];
    const double at_s = pair.far.delivered_at_s()[i];
    if (const auto* alarm = std::get_if<Annotation>(&item)) {
      alarms.insert(alarm->id);
      ++alarm_deliveries;
    } else if (const auto* pose = std::get_if<PoseUpdate>(&item)) {
      if (pose->stamp_s < 95.0 || pose->stamp_s > 135.0) pose_ages_s.push_back(at_s - pose->stamp_s);
    }
  }
  EXPECT_EQ(alarms.size(), team.alarms());
  EXPECT_EQ(alarm_deliveries, team.alarms());
  const double p50 = Percentile(pose_ages_s, 0.5);
  const double p99 = Percentile(pose_ages_s, 0.99);
  EXPECT_LT(p99, 2.0);
  const LinkStats& stats = pair.near_session.stats();
  EXPECT_EQ(pair.far_session.stats().rejected_total(), 0U);
  std::printf("[figures] sealed, 9.6 kbit/s, 0.2 s delay, 5%% loss, outage 100-130 s: pose age p50 %.2f s "
              "p99 %.2f s (%zu poses); maps equal %.1f s after the last change; %zu alarms; "
              "wire bytes near->far %llu (seal %llu, map %llu, pose %llu, annotation %llu, control %llu); "
              "map items resent %llu; frames lost %llu (loss) %llu (outage) %llu (queue)\n",
              p50, p99, pose_ages_s.size(), convergence_s, team.alarms(),
              static_cast<unsigned long long>(stats.wire_bytes_sent),
              static_cast<unsigned long long>(stats.seal_bytes_sent),
              static_cast<unsigned long long>(stats.sent[4].bytes),
              static_cast<unsigned long long>(stats.sent[2].bytes),
              static_cast<unsigned long long>(stats.sent[1].bytes),
              static_cast<unsigned long long>(stats.sent[0].bytes),
              static_cast<unsigned long long>(stats.sent[4].resent),
              static_cast<unsigned long long>(pair.forward_link.stats().dropped_loss),
              static_cast<unsigned long long>(pair.forward_link.stats().dropped_outage),
              static_cast<unsigned long long>(pair.forward_link.stats().dropped_queue));
}

}  // namespace
}  // namespace pena::gateway
