// The link under attack (docs/security.md): two sealed gateway sessions on loopback UDP carry a
// synthetic team's picture while an attacker who can spoof the near gateway's address sends
// 100,000 forged, replayed, bit-flipped, truncated, reflected and foreign-key datagrams at the
// far one. None may be accepted, each must be counted under its status, and the valid traffic
// must all arrive (every valid datagram accepted once, every alarm delivered once, maps equal).
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <random>
#include <set>

#include "pena/gateway/link_crypto.hpp"
#include "pena/gateway/link_session.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/gateway/udp_link.hpp"

namespace pena::gateway {
namespace {

constexpr std::size_t kAttacks = 100000;
constexpr double kStartS = 1.7e9;  // the sessions' clock (simulated, advanced per step)

std::size_t Index(FrameStatus status) { return static_cast<std::size_t>(status); }

// Two UdpLinks on 127.0.0.1 that name each other as peer (ports picked by the kernel).
struct UdpPair {
  UdpPair() {
    UdpLinkOptions probe;
    probe.peer_port = 9;  // replaced below, once the near port is known
    auto far_probe = std::make_unique<UdpLink>(probe);
    const std::uint16_t far_port = far_probe->port();
    UdpLinkOptions near_options;
    near_options.peer_port = far_port;
    near = std::make_unique<UdpLink>(near_options);
    far_probe.reset();
    UdpLinkOptions far_options;
    far_options.bind_port = far_port;
    far_options.peer_port = near->port();
    far = std::make_unique<UdpLink>(far_options);
  }
  std::unique_ptr<UdpLink> near;
  std::unique_ptr<UdpLink> far;
};

// Reads datagrams until `expected` arrived or 2 s passed (loopback does not lose them while the
// receive buffer has room; each step sends far less than it holds).
std::vector<std::string> ReceiveAll(UdpLink& link, std::size_t expected) {
  std::vector<std::string> got;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (got.size() < expected && std::chrono::steady_clock::now() < deadline) {
    for (std::string& datagram : link.Receive(0.05)) got.push_back(std::move(datagram));
  }
  return got;
}

TEST(LinkAttack, HundredThousandHostileDatagramsOverUdpAreAllRefusedAndCounted) {
  LinkKey key;
  for (std::size_t i = 0; i < key.bytes.size(); ++i) key.bytes[i] = static_cast<std::uint8_t>(31 * i + 5);
  LinkKey other_key = GenerateLinkKey();
  while (other_key.id() == key.id()) other_key = GenerateLinkKey();
  LinkOptions near_options;
  near_options.session = 1;
  near_options.key = key;
  LinkOptions far_options = near_options;
  far_options.session = 2;
  InMemoryDomain near_domain, far_domain;
  LinkSession near(near_options, near_domain);
  LinkSession far(far_options, far_domain);
  LinkSeal foreign(other_key);  // the attacker's own key: another link's, or a guess
  UdpPair udp;
  SyntheticTeamOptions team_options;
  team_options.start_s = kStartS;
  team_options.alarm_period_s = 5.0;
  team_options.map_until_s = kStartS + 50.0;
  SyntheticTeam team(team_options);

  std::mt19937_64 random(12345);
  std::vector<std::pair<double, std::string>> accepted;  // valid datagrams far accepted, with time
  std::vector<std::string> from_far;                     // far's own datagrams, to reflect
  std::array<std::size_t, kFrameStatusCount> expected{};
  std::size_t valid_sent = 0, attacks_sent = 0;
  const std::uint8_t key_id = key.id();
  // What the far end must make of a damaged copy of a valid datagram.
  auto damaged_status = [&](const std::string& datagram) {
    if (datagram.size() < kSealOverheadBytes) return FrameStatus::kTruncated;
    return static_cast<std::uint8_t>(datagram[0]) == key_id ? FrameStatus::kUnauthenticated
                                                             : FrameStatus::kWrongKey;
  };
  // One hostile datagram of the given kind, and the status it must get.
  auto attack = [&](std::size_t kind, double now_s) -> std::pair<std::string, FrameStatus> {
    // Valid datagrams of the last 30 s (well inside the 60 s clock limit and the window's age).
    std::size_t first = 0;
    while (first + 1 < accepted.size() && accepted[first].first < now_s - 30.0) ++first;
    const std::string& valid = accepted[first + random() % (accepted.size() - first)].second;
    switch (kind) {
      case 0: {  // forged: random bytes behind the right key id
        std::string forged(kSealOverheadBytes + random() % 600, '\0');
        for (char& c : forged) c = static_cast<char>(random());
        forged[0] = static_cast<char>(key_id);
        return {forged, FrameStatus::kUnauthenticated};
      }
      case 1:  // replayed: a valid datagram again
        return {valid, FrameStatus::kReplayed};
      case 2: {  // one bit flipped anywhere
        std::string flipped = valid;
        const std::size_t byte = random() % flipped.size();
        flipped[byte] = static_cast<char>(flipped[byte] ^ (1 << (random() % 8)));
        return {flipped, damaged_status(flipped)};
      }
      case 3: {  // truncated at any length
        const std::string cut = valid.substr(0, random() % valid.size());
        return {cut, damaged_status(cut)};
      }
      case 4:  // reflected: the far end's own datagram sent back to it
        return {from_far[random() % from_far.size()], FrameStatus::kReflected};
      default:  // sealed under another key
        return {foreign.Seal(EncodeFrame("forged envelope", false), now_s), FrameStatus::kWrongKey};
    }
  };

  double now_s = kStartS;
  const double step_s = 0.01;
  // 90 s: the team acts for 70 s, attacks run from 5 s to 65 s (about 17 per step), then the link
  // drains. Alarms are raised until 60 s, so each has time for its resends.
  for (int step = 0; now_s < kStartS + 90.0; ++step) {
    now_s = kStartS + step_s * step;
    near_domain.set_clock(now_s);
    far_domain.set_clock(now_s);
    if (now_s < kStartS + 60.0) {
      for (DomainItem& item : team.Advance(now_s)) near_domain.Offer(std::move(item));
    }
    std::size_t to_far = 0;
    std::vector<std::string> sent_valid;
    for (std::string& datagram : near.Poll(now_s)) {
      ASSERT_TRUE(udp.near->Send(datagram, nullptr));
      sent_valid.push_back(std::move(datagram));
      ++to_far;
    }
    valid_sent += sent_valid.size();
    const double attack_from_s = kStartS + 5.0, attack_until_s = kStartS + 65.0;
    if (now_s >= attack_from_s && now_s < attack_until_s && !accepted.empty() && !from_far.empty()) {
      const double share = (now_s - attack_from_s + step_s) / (attack_until_s - attack_from_s);
      const auto due = std::min(kAttacks, static_cast<std::size_t>(share * static_cast<double>(kAttacks)));
      for (; attacks_sent < due; ++attacks_sent, ++to_far) {
        auto [datagram, status] = attack(attacks_sent % 6, now_s);
        ++expected[Index(status)];
        // Spoofed: it leaves from the near gateway's address, as an attacker's forgery would.
        ASSERT_TRUE(udp.near->Send(datagram, nullptr));
      }
    }
    const std::vector<std::string> arrived = ReceiveAll(*udp.far, to_far);
    ASSERT_EQ(arrived.size(), to_far) << "loopback lost datagrams at step " << step;
    for (const std::string& datagram : arrived) {
      if (far.OnFrame(datagram, now_s).ok()) accepted.emplace_back(now_s, datagram);
    }
    std::size_t to_near = 0;
    for (std::string& datagram : far.Poll(now_s)) {
      ASSERT_TRUE(udp.far->Send(datagram, nullptr));
      from_far.push_back(std::move(datagram));
      ++to_near;
    }
    for (const std::string& datagram : ReceiveAll(*udp.near, to_near)) near.OnFrame(datagram, now_s);
  }
  ASSERT_EQ(attacks_sent, kAttacks);

  // Nothing hostile accepted: exactly the valid datagrams, each once.
  const LinkStats& stats = far.stats();
  EXPECT_EQ(stats.frames_received, valid_sent);
  EXPECT_EQ(accepted.size(), valid_sent);
  std::set<std::string> distinct;
  for (const auto& [at_s, datagram] : accepted) distinct.insert(datagram);
  EXPECT_EQ(distinct.size(), valid_sent);
  // Every hostile datagram counted under the status it was built to get.
  EXPECT_EQ(stats.rejected_total(), kAttacks);
  for (std::size_t s = 1; s < kFrameStatusCount; ++s) {
    EXPECT_EQ(stats.rejected[s], expected[s]) << ToString(static_cast<FrameStatus>(s));
  }
  EXPECT_EQ(near.stats().rejected_total(), 0U);
  // The valid traffic got through: every alarm once, the maps equal, nothing pending.
  std::set<std::pair<std::string, std::uint64_t>> alarm_keys;
  std::size_t alarm_deliveries = 0;
  for (const DomainItem& item : far_domain.delivered()) {
    if (const auto* alarm = std::get_if<Annotation>(&item)) {
      alarm_keys.emplace(alarm->entity, alarm->id);
      ++alarm_deliveries;
    }
  }
  EXPECT_EQ(alarm_deliveries, team.alarms());
  EXPECT_EQ(alarm_keys.size(), team.alarms());
  for (const auto& [map_id, map] : team.maps()) {
    const auto found = far_domain.maps().find(map_id);
    ASSERT_NE(found, far_domain.maps().end()) << map_id;
    EXPECT_TRUE(line_map::SameMap(found->second.Snapshot(), map.Snapshot())) << map_id;
  }
  EXPECT_EQ(near.scheduler().pending_deltas(), 0U);
  std::printf("[figures] %zu valid datagrams accepted (%zu alarms, %zu maps equal); %zu hostile refused:",
              valid_sent, team.alarms(), team.maps().size(), static_cast<std::size_t>(stats.rejected_total()));
  for (std::size_t s = 1; s < kFrameStatusCount; ++s) {
    if (stats.rejected[s] != 0) {
      std::printf(" %s %llu", ToString(static_cast<FrameStatus>(s)),
                  static_cast<unsigned long long>(stats.rejected[s]));
    }
  }
  std::printf("\n");
}

}  // namespace
}  // namespace pena::gateway
