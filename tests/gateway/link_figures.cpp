// Prints the link encoding figures of docs/gateway.md: bytes per pose and per map segment
// (gateway packing vs the line_map.proto encoding), and what deflate saves on whole frames.
// Usage: gateway_link_figures   (deterministic: the synthetic team's seed is fixed)
#include <cstdio>

#include "link_pair.hpp"
#include "pena/gateway/compression.hpp"
#include "pena/gateway/link_codec.hpp"
#include "pena/line_map/map_packing.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/io/line_map_codec.hpp"

namespace pena::gateway {
namespace {

void PoseFigures() {
  link::Envelope envelope;
  envelope.set_schema_version(kLinkSchemaVersion);
  envelope.set_packet_seq(1234);
  envelope.set_base_stamp_ms(StampMs(1.7e9));
  const std::size_t empty = envelope.ByteSizeLong();
  for (int i = 0; i < 4; ++i) {
    ToProto(PoseUpdate{"ff" + std::to_string(i + 1), {23.45 + i, 41.2, 2.1}, 1.7e9 - 0.3 * i},
            envelope.base_stamp_ms(), envelope.add_items());
  }
  const std::size_t full = envelope.ByteSizeLong();
  std::printf("pose: %.1f bytes per pose in an envelope (entity \"ffN\"); empty envelope %zu bytes;"
              " 4 poses in one frame: %zu bytes + %zu frame + 28 IPv4/UDP = %zu bytes\n",
              static_cast<double>(full - empty) / 4.0, empty, full, std::size_t{10}, full + 10 + 28);
}

void SegmentFigures() {
  SyntheticTeamOptions options;
  options.alarm_period_s = 0.0;
  SyntheticTeam team(options);
  std::size_t segments = 0, removed = 0, deltas = 0, packed = 0, proto = 0, deflated = 0;
  for (DomainItem& item : team.Advance(300.0)) {
    const auto* change = std::get_if<MapChange>(&item);
    if (change == nullptr) continue;
    const auto& delta = std::get<line_map::MapDelta>(change->change);
    ++deltas;
    segments += delta.added.size() + delta.changed.size();
    removed += delta.removed.size();
    const std::string bytes = line_map::PackDelta(delta);
    packed += bytes.size();
    proto += io::EncodeDelta(delta).size();
    deflated += std::min(bytes.size(), Deflate(bytes).size());
  }
  std::size_t map_segments = 0;
  for (const auto& [id, map] : team.maps()) map_segments += map.size();
  std::printf("segments: %zu deltas over 300 s (4 entities), %zu segments sent (added+changed), "
              "%zu removed; final maps %zu segments\n", deltas, segments, removed, map_segments);
  std::printf("  gateway packing: %zu bytes = %.1f bytes/segment; deflated per delta %.1f; "
              "line_map.proto encoding: %.1f bytes/segment\n",
              packed, double(packed) / double(segments), double(deflated) / double(segments),
              double(proto) / double(segments));
}

// The e2e scenario's wire bytes with and without frame compression.
std::uint64_t WireBytes(bool compress) {
  LinkOptions near = testing::Endpoint(1);
  near.compress = compress;
  EmulatedLinkOptions link = testing::IdealLink();
  link.rate_bit_s = 9600.0;
  testing::LinkPair pair(near, testing::Endpoint(2), link, link);
  SyntheticTeamOptions options;
  options.map_until_s = 200.0;
  SyntheticTeam team(options);
  while (pair.now_s < 240.0) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
  }
  std::uint64_t map_bytes = pair.near_session.stats().sent[static_cast<std::size_t>(ItemClass::kMap)].bytes;
  std::printf("  compress=%d: %llu wire bytes near->far in 240 s (map items %llu bytes before "
              "compression), %zu frames\n", compress ? 1 : 0,
              static_cast<unsigned long long>(pair.near_session.stats().wire_bytes_sent),
              static_cast<unsigned long long>(map_bytes), pair.sent_forward.size());
  return pair.near_session.stats().wire_bytes_sent;
}

}  // namespace
}  // namespace pena::gateway

int main() {
  pena::gateway::PoseFigures();
  pena::gateway::SegmentFigures();
  std::printf("compression (9.6 kbit/s, 4 entities, maps for 200 s):\n");
  const double off = static_cast<double>(pena::gateway::WireBytes(false));
  const double on = static_cast<double>(pena::gateway::WireBytes(true));
  std::printf("  deflate saves %.1f %% of the wire bytes\n", 100.0 * (1.0 - on / off));
  return 0;
}
