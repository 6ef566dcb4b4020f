#include "link_runner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <type_traits>

#include "pena/gateway/domain_side.hpp"
#include "pena/line_map/map_packing.hpp"

namespace pena::gateway {
namespace {

double WallClockS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// FNV-1a of a map's packed snapshot and version: equal digests mean equal maps.
std::string Digest(const line_map::LineMap& map) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (char byte : line_map::PackSnapshot(map.Snapshot()) + std::to_string(map.version())) {
    hash = (hash ^ static_cast<std::uint8_t>(byte)) * 1099511628211ULL;
  }
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1))];
}

void PutMaps(std::ostringstream& json, const std::map<std::string, line_map::LineMap>& maps) {
  json << "\"maps\": {";
  const char* separator = "";
  for (const auto& [map_id, map] : maps) {
    json << separator << "\"" << map_id << "\": {\"version\": " << map.version()
         << ", \"segments\": " << map.size() << ", \"digest\": \"" << Digest(map) << "\"}";
    separator = ", ";
  }
  json << "}";
}

// A DDS side's maps: those it sends (mirrors of its DDS maps) and those it received.
std::map<std::string, line_map::LineMap> MapsOf(const DdsDomain& dds) {
  std::map<std::string, line_map::LineMap> maps = dds.sent_maps();
  for (const auto& [map_id, map] : dds.record().maps()) maps.try_emplace(map_id, map);
  return maps;
}

void PutDdsStats(std::ostringstream& json, const DdsDomainStats& stats) {
  json << ", \"dds\": {\"samples_read\": " << stats.samples_read
       << ", \"samples_dropped\": " << stats.samples_dropped
       << ", \"samples_published\": " << stats.samples_published
       << ", \"publish_failures\": " << stats.publish_failures
       << ", \"stale_deltas\": " << stats.stale_deltas
       << ", \"snapshots_forwarded\": " << stats.snapshots_forwarded
       << ", \"sync_requests_sent\": " << stats.sync_requests_sent
       << ", \"sync_requests_answered\": " << stats.sync_requests_answered
       << ", \"samples_refused\": " << stats.samples_refused << "}";
}

// Whether the link is sealed, what the seal cost, and the rejected datagrams by status.
void PutSecurity(std::ostringstream& json, const RunnerOptions& options, const LinkStats& stats) {
  json << ", \"sealed\": " << (options.link.key ? "true" : "false");
  if (options.link.key) json << ", \"key_fingerprint\": \"" << options.link.key->Fingerprint() << "\"";
  json << ", \"seal_bytes_sent\": " << stats.seal_bytes_sent << ", \"rejected\": {";
  const char* separator = "";
  for (std::size_t s = 1; s < kFrameStatusCount; ++s) {
    if (stats.rejected[s] == 0) continue;
    json << separator << "\"" << ToString(static_cast<FrameStatus>(s)) << "\": " << stats.rejected[s];
    separator = ", ";
  }
  json << "}";
}

// The summary: this side's maps, what it received, what it sent per class.
std::string Summary(const RunnerOptions& options, const LinkSession& session,
                    const InMemoryDomain& domain, const SyntheticTeam* team, const DdsDomain* dds,
                    double last_change_s) {
  std::vector<double> ages_s;
  std::size_t alarms = 0;
  double last_pose_at_s = -1.0;
  double max_gap_s = 0.0;  // longest time without a fresh pose: outage plus recovery
  for (std::size_t i = 0; i < domain.delivered().size(); ++i) {
    if (const auto* pose = std::get_if<PoseUpdate>(&domain.delivered()[i])) {
      const double at_s = domain.delivered_at_s()[i];
      ages_s.push_back(at_s - pose->stamp_s);
      if (last_pose_at_s >= 0.0) max_gap_s = std::max(max_gap_s, at_s - last_pose_at_s);
      last_pose_at_s = at_s;
    }
    alarms += std::holds_alternative<Annotation>(domain.delivered()[i]) ? 1 : 0;
  }
  const LinkStats& stats = session.stats();
  std::ostringstream json;
  json.precision(6);
  json << std::fixed << "{\"name\": \"" << options.name << "\", ";
  PutMaps(json, team != nullptr ? team->maps() : dds != nullptr ? MapsOf(*dds) : domain.maps());
  json << ", \"last_map_change_s\": " << last_change_s << ", \"poses_received\": " << ages_s.size()
       << ", \"pose_age_p50_s\": " << Percentile(ages_s, 0.5)
       << ", \"pose_age_p99_s\": " << Percentile(ages_s, 0.99)
       << ", \"pose_age_max_s\": " << Percentile(ages_s, 1.0) << ", \"max_pose_gap_s\": " << max_gap_s
       << ", \"alarms_received\": " << alarms
       << ", \"frames_sent\": " << stats.frames_sent << ", \"wire_bytes_sent\": " << stats.wire_bytes_sent
       << ", \"frames_received\": " << stats.frames_received
       << ", \"frames_rejected\": " << stats.rejected_total();
  PutSecurity(json, options, stats);
  json << ", \"resyncs\": " << stats.resyncs
       << ", \"updates_reassembled\": " << stats.updates_reassembled
       << ", \"reassembled_invalid\": " << stats.reassembled_invalid
       << ", \"pending_deltas\": " << session.scheduler().pending_deltas();
  if (dds != nullptr) PutDdsStats(json, dds->stats());
  json << ", \"sent\": {";
  for (std::size_t c = 0; c < kItemClassCount; ++c) {
    json << (c ? ", " : "") << "\"" << ToString(static_cast<ItemClass>(c)) << "\": {\"items\": "
         << stats.sent[c].items << ", \"bytes\": " << stats.sent[c].bytes
         << ", \"resent\": " << stats.sent[c].resent << "}";
  }
  json << "}}\n";
  return json.str();
}

TcpLinkOptions TcpOptions(const RunnerOptions& options) {
  TcpLinkOptions tcp;
  tcp.listen = options.tcp_listen;
  tcp.bind_address = options.udp.bind_address;
  tcp.bind_port = options.udp.bind_port;
  tcp.peer_address = options.udp.peer_address;
  tcp.peer_port = options.udp.peer_port;
  return tcp;
}

// The synthetic team of --team N (none for 0), starting at start_s on the wall clock.
std::unique_ptr<SyntheticTeam> MakeTeam(const RunnerOptions& options, double start_s) {
  if (options.team_entities <= 0) return nullptr;
  SyntheticTeamOptions team_options = options.team;
  team_options.entities = options.team_entities;
  team_options.start_s = start_s;
  team_options.map_until_s = start_s + options.team.map_until_s;
  return std::make_unique<SyntheticTeam>(team_options);
}

// Delay, loss and outages applied to received frames (the kernel here has no netem).
EmulatedLinkOptions Emulation(const RunnerOptions& options, double start_s) {
  EmulatedLinkOptions emulation;
  emulation.rate_bit_s = 0.0;
  emulation.delay_s = options.emulate_delay_s;
  emulation.loss = options.emulate_loss;
  for (const auto& [from, to] : options.emulate_outages) {
    emulation.outages.emplace_back(start_s + from, start_s + to);
  }
  return emulation;
}

// Logs a rejected datagram: the first 10 of each status, then every 1000th, so a flood of
// forged datagrams cannot flood the log too.
void LogRejected(const std::string& name, const FrameResult& result, const LinkStats& stats) {
  const std::uint64_t count = stats.rejected[static_cast<std::size_t>(result.status)];
  if (count > 10 && count % 1000 != 0) return;
  spdlog::warn("{}: rejected datagram ({} {} so far): {}", name, count, ToString(result.status),
               result.message);
}

// The link's health for the operator's console, over the window since `previous`.
class HealthReporter {
 public:
  HealthReporter(std::string name, double start_s) : name_(std::move(name)), last_s_(start_s) {}
  // Publishes once per second.
  void Maybe(DdsDomain& dds, const LinkSession& session, double now_s) {
    const double window_s = now_s - last_s_;
    if (window_s < 1.0) return;
    const LinkStats& stats = session.stats();
    pena_dds::LinkHealth health;
    health.gateway_id(name_.substr(0, 32));
    health.schema_version(pena_dds::SCHEMA_VERSION);
    health.peer_alive(session.peer_alive(now_s));
    health.peer_heard_age_s(session.last_heard_s() < 0.0 ? -1.0 : now_s - session.last_heard_s());
    health.budget_bit_s(session.options().budget_bit_s);
    health.sent_bit_s(8.0 * static_cast<double>(stats.wire_bytes_sent - wire_bytes_) / window_s);
    health.received_frames_s(static_cast<double>(stats.frames_received - frames_received_) / window_s);
    health.pending_reliable(static_cast<std::uint32_t>(session.scheduler().pending_annotations()));
    health.pending_map_updates(static_cast<std::uint32_t>(session.scheduler().pending_deltas()));
    health.frames_rejected(stats.rejected_total());
    health.resyncs(stats.resyncs);
    dds.PublishLinkHealth(health);
    wire_bytes_ = stats.wire_bytes_sent;
    frames_received_ = stats.frames_received;
    last_s_ = now_s;
  }

 private:
  std::string name_;
  double last_s_;
  std::uint64_t wire_bytes_ = 0;
  std::uint64_t frames_received_ = 0;
};

// The loop, for either transport (UdpLink or TcpLink: Send, Receive).
template <typename Transport>
std::string Run(const RunnerOptions& options, Transport& link,
                const std::function<bool()>& stop_requested) {
  InMemoryDomain memory;
  std::unique_ptr<DdsDomain> dds;
  if (options.dds) dds = std::make_unique<DdsDomain>(options.dds_options);
  DomainSide& side = dds ? static_cast<DomainSide&>(*dds) : memory;
  const InMemoryDomain& domain = dds ? dds->record() : memory;
  LinkSession session(options.link, side);
  const double start_s = WallClockS();
  std::unique_ptr<SyntheticTeam> team = MakeTeam(options, start_s);
  EmulatedLink inbound(Emulation(options, start_s));
  spdlog::info("{}: {} {}:{} -> {}:{}, budget {} bit/s, session {:x}", options.name,
               options.tcp ? "tcp" : "udp", options.udp.bind_address, options.udp.bind_port,
               options.udp.peer_address,
               options.udp.peer_port, options.link.budget_bit_s, session.session());
  if (options.link.key) {
    spdlog::info("{}: link sealed (XChaCha20-Poly1305), key fingerprint {}", options.name,
                 options.link.key->Fingerprint());
  } else {
    spdlog::warn("{}: OPEN LINK (--insecure-link): frames are neither authenticated nor encrypted",
                 options.name);
  }
  if (dds) {
    std::string send, publish;
    for (DdsClass c : options.dds_options.role.send) send += std::string(send.empty() ? "" : ",") + ToString(c);
    for (DdsClass c : options.dds_options.role.publish) publish += std::string(publish.empty() ? "" : ",") + ToString(c);
    spdlog::info("{}: DDS domain {} (profile {}), sends [{}], publishes [{}]", options.name,
                 options.dds_options.dds.domain_id, options.dds_options.dds.participant_profile, send, publish);
  }
  double last_change_s = 0.0;
  std::uint64_t send_errors = 0;
  HealthReporter health(options.name, start_s);
  while (!stop_requested() && (options.duration_s <= 0.0 || WallClockS() - start_s < options.duration_s)) {
    for (std::string& frame : link.Receive(0.005)) inbound.Send(std::move(frame), WallClockS());
    const double now_s = WallClockS();
    if (dds) dds->set_clock(now_s);
    memory.set_clock(now_s);
    for (const std::string& frame : inbound.Receive(now_s)) {
      const std::size_t before = domain.delivered().size();
      const FrameResult result = session.OnFrame(frame, now_s);
      if (!result.ok()) LogRejected(options.name, result, session.stats());
      for (std::size_t i = before; i < domain.delivered().size(); ++i) {
        if (std::holds_alternative<MapChange>(domain.delivered()[i])) last_change_s = now_s;
      }
    }
    if (team) {
      for (DomainItem& item : team->Advance(now_s)) memory.Offer(std::move(item));
      last_change_s = std::max(0.0, team->last_map_change_s());
    }
    if (dds) {
      last_change_s = std::max(last_change_s, dds->last_sent_map_change_s());
      health.Maybe(*dds, session, now_s);
    }
    for (const std::string& frame : session.Poll(now_s)) {
      std::string error;
      if (!link.Send(frame, &error) && send_errors++ % 100 == 0) {
        spdlog::warn("{}: send failed ({} so far): {}", options.name, send_errors, error);
      }
    }
  }
  if constexpr (std::is_same_v<Transport, TcpLink>) {
    spdlog::info("{}: tcp connection lost {} times (last: {})", options.name, link.drops(), link.last_drop());
  }
  const std::string json = Summary(options, session, domain, team.get(), dds.get(), last_change_s);
  if (!options.stats_path.empty()) std::ofstream(options.stats_path) << json;
  return json;
}

}  // namespace

std::string RunGateway(const RunnerOptions& options,
                       const std::function<bool()>& stop_requested) {
  if (options.tcp) {
    TcpLink tcp(TcpOptions(options));
    return Run(options, tcp, stop_requested);
  }
  UdpLink udp(options.udp);
  return Run(options, udp, stop_requested);
}

}  // namespace pena::gateway
