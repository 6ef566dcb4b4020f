// Prints what the link seal costs (docs/security.md): bytes per datagram and their share of a
// 9.6 kbit/s link in the synthetic team scenario, sealed against open (pose age, map convergence),
// and seal/open throughput on this machine.
// Usage: gateway_link_seal_figures   (the scenario is deterministic; the throughput is not)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "link_pair.hpp"
#include "team_checks.hpp"
#include "pena/gateway/link_crypto.hpp"
#include "pena/gateway/synthetic_team.hpp"

namespace pena::gateway {
namespace {

using testing::MapsEqual;
using testing::Percentile;

constexpr double kRateBitS = 9600.0;

// The team scenario of gateway_link_figures (4 entities, maps for 200 s, 240 s) through an
// emulated 9.6 kbit/s link with 0.2 s delay, sealed or open.
void Scenario(bool sealed) {
  LinkOptions near = testing::Endpoint(1);
  LinkOptions far = testing::Endpoint(2);
  if (sealed) near.key = far.key = GenerateLinkKey();
  EmulatedLinkOptions link = testing::IdealLink();
  link.rate_bit_s = kRateBitS;
  link.delay_s = 0.2;
  testing::LinkPair pair(near, far, link, link);
  SyntheticTeamOptions options;
  options.map_until_s = 200.0;
  SyntheticTeam team(options);
  double converged_s = -1.0;
  while (pair.now_s < 240.0) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
    if (converged_s < 0.0 && pair.now_s > team.last_map_change_s() && MapsEqual(team, pair.far)) {
      converged_s = pair.now_s - team.last_map_change_s();
    }
  }
  std::vector<double> ages_s;
  for (std::size_t i = 0; i < pair.far.delivered().size(); ++i) {
    if (const auto* pose = std::get_if<PoseUpdate>(&pair.far.delivered()[i])) {
      ages_s.push_back(pair.far.delivered_at_s()[i] - pose->stamp_s);
    }
  }
  const LinkStats& stats = pair.near_session.stats();
  const double seconds = pair.now_s;
  const double frame_bytes = static_cast<double>(stats.frame_bytes_sent) / static_cast<double>(stats.frames_sent);
  std::printf("  %-6s: %llu datagrams, %.1f B each (seal %llu B in all), wire %llu B = %.0f bit/s = "
              "%.1f %% of 9.6 kbit/s; seal %.0f bit/s = %.2f %% of 9.6 kbit/s; %zu poses at the far "
              "end, age p50 %.2f s p99 %.2f s; maps equal %.1f s after the last change\n",
              sealed ? "sealed" : "open", static_cast<unsigned long long>(stats.frames_sent), frame_bytes,
              static_cast<unsigned long long>(stats.seal_bytes_sent),
              static_cast<unsigned long long>(stats.wire_bytes_sent),
              8.0 * static_cast<double>(stats.wire_bytes_sent) / seconds,
              100.0 * 8.0 * static_cast<double>(stats.wire_bytes_sent) / seconds / kRateBitS,
              8.0 * static_cast<double>(stats.seal_bytes_sent) / seconds,
              100.0 * 8.0 * static_cast<double>(stats.seal_bytes_sent) / seconds / kRateBitS,
              ages_s.size(), Percentile(ages_s, 0.5), Percentile(ages_s, 0.99), converged_s);
}

// Seal and open of one frame size, timed over enough rounds to take about half a second.
void Throughput(std::size_t frame_bytes) {
  const LinkKey key = GenerateLinkKey();
  SealOptions options;
  options.sender_id = 1;
  LinkSeal near(key, options);
  options.sender_id = 2;
  options.max_clock_offset_s = 0.0;
  LinkSeal far(key, options);
  const std::string frame(frame_bytes, 'x');
  constexpr int kRounds = 100000;
  std::vector<std::string> sealed;
  sealed.reserve(kRounds);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  for (int i = 0; i < kRounds; ++i) sealed.push_back(near.Seal(frame, 1.7e9));
  const auto sealed_at = Clock::now();
  std::size_t opened = 0;
  for (const std::string& datagram : sealed) opened += far.Open(datagram, 1.7e9).ok() ? 1 : 0;
  const auto opened_at = Clock::now();
  const double seal_s = std::chrono::duration<double>(sealed_at - start).count();
  const double open_s = std::chrono::duration<double>(opened_at - sealed_at).count();
  std::printf("  %4zu-byte frames: seal %.2f us (%.0f MB/s), open %.2f us (%.0f MB/s) per datagram; "
              "%zu of %d opened\n",
              frame_bytes, 1e6 * seal_s / kRounds, static_cast<double>(frame_bytes) * kRounds / seal_s / 1e6,
              1e6 * open_s / kRounds, static_cast<double>(frame_bytes) * kRounds / open_s / 1e6, opened, kRounds);
}

}  // namespace
}  // namespace pena::gateway

int main() {
  using pena::gateway::kSealOverheadBytes;
  std::printf("seal: %zu bytes per datagram (header %zu: key id, sender id, counter; Poly1305 tag %zu)\n",
              kSealOverheadBytes, pena::gateway::kSealHeaderBytes, pena::gateway::kSealTagBytes);
  const std::size_t full = 480 + pena::gateway::kFrameHeaderBytes + pena::gateway::kFrameTrailerBytes +
                           kSealOverheadBytes + 28;
  std::printf("a full 480-byte packet: %zu bytes on the wire with IPv4/UDP, the seal %.1f %% of them\n", full,
              100.0 * static_cast<double>(kSealOverheadBytes) / static_cast<double>(full));
  std::printf("team scenario (4 entities, maps for 200 s, 240 s, 9.6 kbit/s emulated, 0.2 s delay), near->far:\n");
  pena::gateway::Scenario(false);
  pena::gateway::Scenario(true);
  std::printf("throughput (XChaCha20-Poly1305, libsodium, one core):\n");
  for (std::size_t bytes : {131U, 480U, 1400U}) pena::gateway::Throughput(bytes);
  return 0;
}
