// pena-gateway: bridges a local domain across a bandwidth-limited link (docs/gateway.md).
// The local domain is a DDS domain (--dds-domain, --role), a synthetic team (--team N) or
// receive-only. The link is sealed with --link-key FILE, or open with --insecure-link
// (docs/security.md). Logs like the other daemons (services/common/logging.hpp): to the
// journal with syslog priorities under systemd, else to stderr, optionally also to a file.
// Exits 0 on success, 1 on bad options or a failure, 2 on a DDS failure.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "daemon_main.hpp"
#include "dds_participant.hpp"
#include "link_runner.hpp"
#include "signals.hpp"

namespace {

// "host:port" into its parts; throws CLI::ValidationError naming the option.
void SplitEndpoint(const std::string& text, const std::string& option, std::string* host,
                   std::uint16_t* port) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) throw CLI::ValidationError(option, "expected HOST:PORT, got " + text);
  *host = text.substr(0, colon);
  const long value = std::strtol(text.c_str() + colon + 1, nullptr, 10);
  if (value < 0 || value > 65535) throw CLI::ValidationError(option, "port out of range: " + text);
  *port = static_cast<std::uint16_t>(value);
}

// The link key flags (docs/security.md).
struct KeyFlags {
  std::string key_file;
  std::string generate_file;
  bool insecure = false;
};

void AddKeyOptions(CLI::App& app, pena::gateway::RunnerOptions& options, KeyFlags& flags) {
  app.add_option("--link-key", flags.key_file,
                 "the link's key file (64 hex digits, mode 0600; both ends hold the same one); "
                 "required unless --insecure-link");
  app.add_flag("--insecure-link", flags.insecure,
               "open frames: neither authenticated nor encrypted (experiments only)");
  app.add_option("--generate-link-key", flags.generate_file,
                 "write a new random link key to FILE (mode 0600), print its fingerprint and exit");
  app.add_option("--link-max-clock-offset-s", options.link.seal.max_clock_offset_s,
                 "refuse sealed frames stamped further from this gateway's clock (s; 0: no check)")
      ->capture_default_str();
}

// Checks the key flags; throws CLI::ValidationError naming the option. The key itself is read
// after parsing (ReadLinkKey), so a bad key file is reported as such.
void CheckKeyFlags(const KeyFlags& flags, const pena::gateway::RunnerOptions& options) {
  if (!flags.key_file.empty() && flags.insecure) {
    throw CLI::ValidationError("--link-key", "and --insecure-link exclude each other");
  }
  if (flags.key_file.empty() && !flags.insecure) {
    throw CLI::ValidationError("--link-key",
                               "no link key: pass --link-key FILE (make one with --generate-link-key "
                               "FILE; docs/security.md), or --insecure-link for an open link in experiments");
  }
  if (options.tcp && !flags.insecure) {
    throw CLI::ValidationError("--tcp", "carries open frames only (it exists for the transport "
                                        "measurement): use --insecure-link");
  }
}

// Writes a new key for --generate-link-key; throws if the file cannot be written.
void GenerateKey(const std::string& path) {
  const pena::gateway::LinkKey key = pena::gateway::GenerateLinkKey();
  pena::gateway::WriteLinkKey(path, key);
  std::printf("wrote link key %s (fingerprint %s); copy it to both gateways of the link\n",
              path.c_str(), key.Fingerprint().c_str());
}

// Registers every command-line option; the endpoints and outages are parsed after.
void AddOptions(CLI::App& app, pena::gateway::RunnerOptions& options, std::string& bind,
                std::string& peer, bool& no_compress, std::vector<std::string>& outages) {
  app.add_option("--bind", bind, "local HOST:PORT (UDP)")->capture_default_str();
  app.add_option("--peer", peer, "the other gateway's HOST:PORT")->capture_default_str();
  app.add_option("--budget-bit-s", options.link.budget_bit_s, "bit budget (keep below the link rate)")->capture_default_str();
  app.add_option("--burst-bits", options.link.burst_bits, "token bucket capacity")->capture_default_str();
  app.add_option("--packet-bytes", options.link.packet_bytes, "target envelope size")->capture_default_str();
  app.add_option("--overhead-bytes", options.link.overhead_bytes, "per-frame bytes below the link frame")->capture_default_str();
  app.add_flag("--no-compress", no_compress, "never deflate frame payloads");
  app.add_flag("--tcp", options.tcp, "TCP instead of UDP (transport measurement)");
  app.add_flag("--tcp-listen", options.tcp_listen, "with --tcp: accept the peer's connection");
  app.add_option("--retransmit-timeout-s", options.link.scheduler.retransmit_timeout_s,
                 "first resend of an unacknowledged item")->capture_default_str();
  app.add_option("--max-retransmit-timeout-s", options.link.scheduler.max_retransmit_timeout_s,
                 "resend timeout cap")->capture_default_str();
  app.add_option("--team", options.team_entities, "publish a synthetic team of N entities (0: receive only)");
  app.add_option("--map-until-s", options.team.map_until_s, "synthetic maps stop changing after this (s)");
  app.add_option("--seed", options.team.seed, "synthetic team seed")->capture_default_str();
  app.add_option("--duration-s", options.duration_s, "run time (s); 0: until SIGINT/SIGTERM")->capture_default_str();
  app.add_option("--emulate-delay-s", options.emulate_delay_s, "delay added to received frames (no netem)");
  app.add_option("--emulate-loss", options.emulate_loss, "probability of dropping a received frame");
  app.add_option("--emulate-outage", outages, "START:END seconds after start: drop everything received");
  app.add_option("--stats", options.stats_path, "write the JSON summary here");
  app.add_option("--name", options.name, "name in logs and the summary");
}

// Where the log goes besides stderr (the journal under systemd), and from which level.
void AddLogOptions(CLI::App& app, pena::services::DaemonLogging& logging) {
  app.add_option("--log-level", logging.level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}))
      ->capture_default_str();
  app.add_option("--log-file", logging.file, "also write the log to this file");
}

// The DDS command line: domain, profiles, role and its overrides.
struct DdsFlags {
  int domain = -1;
  std::vector<std::string> profiles_files;
  std::string participant_profile = "pena_loopback";
  std::string role;
  std::vector<std::string> send;
  std::vector<std::string> publish;
  bool send_given = false;
  bool publish_given = false;
};

void AddDdsOptions(CLI::App& app, pena::gateway::RunnerOptions& options, DdsFlags& flags) {
  app.add_option("--dds-domain", flags.domain, "bridge this DDS domain (0..232); without it: --team or receive-only")
      ->check(CLI::Range(0, 232));
  app.add_option("--role", flags.role, "building | command-post | entities | fusion-post (docs/gateway.md)")
      ->check(CLI::IsMember({"building", "command-post", "entities", "fusion-post"}));
  app.add_option("--send", flags.send, "classes read from DDS and sent (overrides the role): pose, entity_map, global_map, annotation, correction, operator_correction, none")
      ->delimiter(',');
  app.add_option("--publish", flags.publish, "classes received and published into DDS (overrides the role)")
      ->delimiter(',');
  app.add_option("--dds-profiles-file", flags.profiles_files,
                 "Fast DDS XML profile file (repeat; default deploy/dds/pena-loopback.xml and pena-qos.xml)");
  app.add_option("--dds-participant-profile", flags.participant_profile, "participant profile")->capture_default_str();
  app.add_option("--snapshot-grace-s", options.dds_options.snapshot_grace_s,
                 "forward a newer DDS snapshot only if deltas do not reach it within this")->capture_default_str();
}

std::set<pena::gateway::DdsClass> ParseClasses(const std::vector<std::string>& names, const std::string& option) {
  std::set<pena::gateway::DdsClass> classes;
  for (const std::string& name : names) {
    if (name == "none") continue;
    const auto parsed = pena::gateway::ParseDdsClass(name);
    if (!parsed) throw CLI::ValidationError(option, "unknown class '" + name + "'");
    classes.insert(*parsed);
  }
  return classes;
}

// Fills options.dds_options from the flags; throws CLI::ValidationError naming the option.
void ApplyDdsFlags(const CLI::App& app, const DdsFlags& flags, pena::gateway::RunnerOptions& options) {
  const bool any = !flags.role.empty() || app.count("--send") > 0 || app.count("--publish") > 0;
  if (flags.domain < 0) {
    if (any) throw CLI::ValidationError("--role/--send/--publish", "need --dds-domain");
    return;
  }
  if (options.team_entities > 0) throw CLI::ValidationError("--team", "cannot be combined with --dds-domain");
  if (flags.role.empty() && (app.count("--send") == 0 || app.count("--publish") == 0)) {
    throw CLI::ValidationError("--dds-domain", "needs --role, or both --send and --publish");
  }
  options.dds = true;
  auto& dds = options.dds_options;
  if (!flags.role.empty()) dds.role = *pena::gateway::ParseDdsRole(flags.role);
  if (app.count("--send") > 0) dds.role.send = ParseClasses(flags.send, "--send");
  if (app.count("--publish") > 0) dds.role.publish = ParseClasses(flags.publish, "--publish");
  dds.dds.domain_id = flags.domain;
  dds.dds.participant_profile = flags.participant_profile;
  if (flags.profiles_files.empty()) {
    dds.dds.profiles_files = pena::services::DefaultProfilesFiles();
  } else {
    for (const std::string& file : flags.profiles_files) {
      dds.dds.profiles_files.push_back(std::filesystem::absolute(file));
    }
  }
  dds.name = "pena-gateway-" + options.name;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pena-gateway: carries alarms, poses, corrections and line maps across a slow link"};
  pena::gateway::RunnerOptions options;
  std::string bind = "127.0.0.1:7701";
  std::string peer = "127.0.0.1:7702";
  bool no_compress = false;
  std::vector<std::string> outages;
  AddOptions(app, options, bind, peer, no_compress, outages);
  DdsFlags dds_flags;
  AddDdsOptions(app, options, dds_flags);
  KeyFlags key_flags;
  AddKeyOptions(app, options, key_flags);
  pena::services::DaemonLogging logging{"info", {}};
  AddLogOptions(app, logging);
  try {
    app.parse(argc, argv);
    if (key_flags.generate_file.empty()) {
      CheckKeyFlags(key_flags, options);
      SplitEndpoint(bind, "--bind", &options.udp.bind_address, &options.udp.bind_port);
      SplitEndpoint(peer, "--peer", &options.udp.peer_address, &options.udp.peer_port);
      for (const std::string& outage : outages) {
        double from = 0.0;
        double to = 0.0;
        if (std::sscanf(outage.c_str(), "%lf:%lf", &from, &to) != 2 || !(to > from)) {
          throw CLI::ValidationError("--emulate-outage", "expected START:END with END > START, got " + outage);
        }
        options.emulate_outages.emplace_back(from, to);
      }
      ApplyDdsFlags(app, dds_flags, options);
    }
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  options.link.compress = !no_compress;
  return pena::services::RunDaemon(
      "pena-gateway", [&] { return logging; },
      [&] {
        if (!key_flags.generate_file.empty()) {
          GenerateKey(key_flags.generate_file);
          return EXIT_SUCCESS;
        }
        if (!key_flags.key_file.empty()) options.link.key = pena::gateway::ReadLinkKey(key_flags.key_file);
        std::fputs(pena::gateway::RunGateway(options, pena::services::StopRequested).c_str(), stdout);
        return EXIT_SUCCESS;
      });
}
