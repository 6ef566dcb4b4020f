#pragma once
// pena-gateway's event loop: one LinkSession on a UDP socket, a local domain (a DDS domain, a
// synthetic team or a receive-only in-memory domain), optional delay/loss/outage
// emulation on the receive path (where the kernel lacks netem), and a JSON summary at the end.

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "pena/gateway/dds_domain.hpp"
#include "pena/gateway/link_emulator.hpp"
#include "pena/gateway/link_session.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/gateway/tcp_link.hpp"
#include "pena/gateway/udp_link.hpp"

namespace pena::gateway {

// Everything pena-gateway was told on its command line.
struct RunnerOptions {
  UdpLinkOptions udp;
  bool tcp = false;                  // TCP instead of UDP (for the transport measurement)
  bool tcp_listen = false;           // TCP: this side accepts, the other connects
  LinkOptions link;
  int team_entities = 0;             // > 0: publish a synthetic team of this size
  SyntheticTeamOptions team;
  bool dds = false;                  // the local domain is a DDS domain (else synthetic/in-memory)
  DdsDomainOptions dds_options;      // participant, role (send and publish classes)
  double duration_s = 60.0;          // run this long (wall clock), then report; <= 0: until a signal
  double emulate_delay_s = 0.0;      // added to every received frame
  double emulate_loss = 0.0;         // probability of dropping a received frame
  std::vector<std::pair<double, double>> emulate_outages;  // seconds after start: drop all
  std::string stats_path;            // JSON summary written here ("" = stdout only)
  std::string name = "gateway";      // for logs
};

// Runs until duration_s passes or `stop_requested()` is true; returns the JSON summary it wrote.
std::string RunGateway(const RunnerOptions& options, const std::function<bool()>& stop_requested);

}  // namespace pena::gateway
