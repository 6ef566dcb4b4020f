// pena-fusion: the central PeNa fusion service (docs/fusion-service.md). Merges every entity's
// local line map and the a priori plan into the global map, sends corrections, relays operator
// items, and resumes from its state directory after a crash. Runs until SIGINT/SIGTERM; exits 0
// after a clean stop, 1 on bad options, config or state, 2 on a DDS failure.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "config_loader.hpp"
#include "fusion_options.hpp"
#include "fusion_service.hpp"
#include "daemon_main.hpp"
#include "signals.hpp"

namespace {

using pena::services::FusionServiceOptions;

// Command-line values; each given one overrides the config file's.
struct Overrides {
  std::string config, state_dir, plan, output_dir, participant_profile, log_level;
  std::vector<std::string> profiles_files;
  std::string security_dir;
  std::optional<int> domain_id;
  bool no_corrections = false;
  bool raw_corrections = false;
  std::optional<double> correction_interval_s;
  std::optional<double> correction_max_wait_s;
  bool lockstep = false;
  std::vector<std::string> lockstep_entities;
  std::optional<double> lockstep_stall_s;
};

void AddOptions(CLI::App& app, Overrides& o) {
  app.add_option("--config", o.config, "Config file (Protobuf text format, FusionConfig)");
  app.add_option("--state-dir", o.state_dir, "Journal and checkpoint directory");
  app.add_option("--plan", o.plan, "A priori plan (line CSV, SVG or DXF)");
  app.add_option("--out", o.output_dir, "Output directory: global_map.csv, global_wall_support.csv, fusion_stats.json");
  app.add_flag("--no-corrections", o.no_corrections, "Do not send corrections");
  app.add_flag("--raw-corrections", o.raw_corrections,
               "Send the raw match instead of blending it with the entity's uncertainty");
  app.add_option("--correction-interval", o.correction_interval_s,
                 "Seconds between correction attempts per entity (wall; with --lockstep mission)");
  app.add_option("--correction-max-wait", o.correction_max_wait_s,
                 "Drop a reference scan that waited longer than this (wall s; 0 = never)");
  app.add_flag("--lockstep", o.lockstep,
               "Schedule correction attempts on mission time and answer every one (for entities "
               "run with --await-corrections: results independent of the machine's load)");
  app.add_option("--lockstep-entities", o.lockstep_entities,
                 "With --lockstep: entity ids to wait for before the first item is released "
                 "(comma separated; the team the demo starts)")
      ->delimiter(',');
  app.add_option("--lockstep-stall", o.lockstep_stall_s,
                 "With --lockstep: wall seconds an item waits for a silent entity before it is "
                 "released anyway (default 10)");
  app.add_option("--domain", o.domain_id, "DDS domain id (0..232)");
  app.add_option("--profile", o.participant_profile,
                 "Participant profile (default pena_loopback_udp: pena_loopback without shared "
                 "memory)");
  app.add_option("--profiles-file", o.profiles_files, "DDS XML profile file (repeatable)");
  app.add_option("--security", o.security_dir,
                 "DDS Security identity directory (deploy/security/make-identities.sh); default: none, an open participant");
  app.add_option("--log-level", o.log_level, "trace, debug, info, warn, error");
}

FusionServiceOptions BuildOptions(const Overrides& o) {
  pena::services::config::FusionConfig config;
  if (!o.config.empty()) {
    config = pena::services::LoadTextConfig<pena::services::config::FusionConfig>(o.config);
  }
  FusionServiceOptions options = pena::services::FusionOptionsFromConfig(config, o.config);
  if (!o.state_dir.empty()) options.state_dir = o.state_dir;
  if (!o.plan.empty()) options.plan = o.plan;
  if (!o.output_dir.empty()) options.output_dir = o.output_dir;
  if (o.no_corrections) options.corrections = false;
  if (o.raw_corrections) options.filter_corrections = false;
  if (o.correction_interval_s) options.correction_interval_s = *o.correction_interval_s;
  if (o.correction_max_wait_s) options.correction_max_wait_s = *o.correction_max_wait_s;
  if (o.lockstep) options.lockstep = true;
  options.lockstep_order.expected_entities = o.lockstep_entities;
  if (o.lockstep_stall_s) options.lockstep_order.stall_s = *o.lockstep_stall_s;
  if (o.domain_id) options.dds.domain_id = *o.domain_id;
  if (!o.participant_profile.empty()) options.dds.participant_profile = o.participant_profile;
  if (!o.security_dir.empty()) options.dds.security_dir = o.security_dir;
  if (!o.profiles_files.empty()) {
    options.dds.profiles_files.assign(o.profiles_files.begin(), o.profiles_files.end());
  }
  if (!o.log_level.empty()) options.log_level = o.log_level;
  pena::services::ValidateFusionServiceOptions(options);
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-fusion: the central PeNa fusion service");
  Overrides overrides;
  AddOptions(app, overrides);
  CLI11_PARSE(app, argc, argv);
  FusionServiceOptions options;
  const auto build = [&] {
    options = BuildOptions(overrides);
    return pena::services::DaemonLogging{options.log_level, options.log_file};
  };
  return pena::services::RunDaemon("pena-fusion", build, [&] {
    pena::services::FusionService service(std::move(options));
    const pena::services::FusionRunSummary summary = service.Run();
    spdlog::info("stopped: {} inputs ({} refused), global map version {} with {} segments; "
                 "{} deltas, {} snapshots, {} corrections sent",
                 summary.inputs, summary.problems, summary.global_version,
                 summary.global_segments, summary.global_deltas_sent, summary.snapshots_sent,
                 summary.corrections_sent);
    return EXIT_SUCCESS;
  });
}
