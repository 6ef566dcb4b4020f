// pena-entity: the PeNa service of one firefighter or robot (docs/services.md). Reads a sensor
// log at a chosen rate or the live sensor topics (--input dds), runs the per-entity pipeline and talks DDS (docs/dds.md). Exits 0 when
// the input ended or a signal stopped it cleanly, 1 on bad options or input, 2 on a DDS failure.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdlib>

#include "config_loader.hpp"
#include "entity_options.hpp"
#include "entity_service.hpp"
#include "daemon_main.hpp"
#include "pena/io/input_error.hpp"
#include "signals.hpp"

namespace {

using pena::services::EntityServiceOptions;

// Command-line values; each given one overrides the config file's.
struct Overrides {
  std::string config, input, entity_id, kind, output_dir, participant_profile, log_level, plan;
  std::vector<std::string> profiles_files;
  std::string security_dir;
  std::optional<double> rate, wait_for_readers_s, linger_s, await_corrections_s;
  std::optional<double> reorder_window_s, idle_timeout_s, correction_max_chi2;
  std::optional<int> domain_id;
  std::vector<double> hold_at_s;
  bool record = false;
  bool start_unknown = false;
};

void AddOptions(CLI::App& app, Overrides& o) {
  app.add_option("--config", o.config, "Config file (Protobuf text format, EntityConfig)");
  app.add_option("--input", o.input,
                 "sensors.penalog, its entity directory, a CARMEN log, or dds: the live sensor "
                 "topics of --entity-id (./dds for a file named dds)");
  app.add_option("--reorder-window", o.reorder_window_s,
                 "--input dds: sensor seconds a record waits for older records of other topics "
                 "(default 0.2)");
  app.add_option("--idle-timeout", o.idle_timeout_s,
                 "--input dds: end after this many wall seconds without a sample (default 0: "
                 "wait for the end-of-stream marker or a signal)");
  app.add_option("--plan", o.plan,
                 "A priori plan (CSV, SVG or DXF, mission frame): localise against it");
  app.add_option("--entity-id", o.entity_id, "Entity id on the topics (default: the log's)");
  app.add_option("--kind", o.kind, "human or robot (default: the log's)");
  app.add_option("--rate", o.rate, "Time scale: 1 real time, 10 ten times faster, 0 flat out");
  app.add_option("--out", o.output_dir, "Output directory: trajectory.tum, line_map.csv");
  app.add_flag("--record", o.record, "Record sent/received samples under OUT/recording");
  app.add_flag("--unknown-start", o.start_unknown,
               "Ignore the log's start pose: run in the entity's own frame until the fusion "
               "places it");
  app.add_option("--await-corrections", o.await_corrections_s,
                 "Lockstep with pena-fusion --lockstep: wait for the answer to every reference "
                 "scan at least this many mission seconds after the last awaited one (the "
                 "fusion's --correction-interval)");
  app.add_option("--hold-at", o.hold_at_s,
                 "Mission times (the log's stamps, s, comma-separated, increasing) at which to "
                 "stop the clock until SIGUSR1: nothing read or published meanwhile, corrections "
                 "applied; each SIGUSR1 releases one hold (for tests)")
      ->delimiter(',');
  app.add_option("--correction-max-chi2", o.correction_max_chi2,
                 "Hold a correction whose move exceeds this chi-square of the entity's own pose "
                 "covariance (default 16.27: 99.9 % at 3 DoF; 0: no bound); operators' are applied");
  app.add_option("--domain", o.domain_id, "DDS domain id (0..232)");
  app.add_option("--profile", o.participant_profile, "Participant profile (default pena_loopback)");
  app.add_option("--profiles-file", o.profiles_files, "DDS XML profile file (repeatable)");
  app.add_option("--security", o.security_dir,
                 "DDS Security identity directory (deploy/security/make-identities.sh); default: none, an open participant");
  app.add_option("--wait-for-readers", o.wait_for_readers_s,
                 "Wait up to this many seconds for the fusion's readers before starting");
  app.add_option("--linger", o.linger_s, "Seconds to wait for acknowledgements at the end");
  app.add_option("--log-level", o.log_level, "trace, debug, info, warn, error");
}

EntityServiceOptions BuildOptions(const Overrides& o) {
  pena::services::config::EntityConfig config;
  if (!o.config.empty()) {
    config = pena::services::LoadTextConfig<pena::services::config::EntityConfig>(o.config);
  }
  EntityServiceOptions options = pena::services::EntityOptionsFromConfig(config, o.config);
  if (!o.input.empty()) options.input = o.input;
  if (!pena::services::IsLiveInput(options.input) && std::filesystem::is_directory(options.input)) {
    options.input /= "sensors.penalog";
  }
  if (o.reorder_window_s) options.live.merge.reorder_window_s = *o.reorder_window_s;
  if (o.idle_timeout_s) options.live.idle_timeout_s = *o.idle_timeout_s;
  if (!o.plan.empty()) options.plan = o.plan;
  if (!o.entity_id.empty()) options.entity_id = o.entity_id;
  if (!o.kind.empty()) {
    options.kind = pena::sensors::ParseEntityKind(o.kind);
    if (!options.kind) throw std::invalid_argument("--kind must be human or robot");
  }
  if (o.rate) options.rate = *o.rate;
  if (!o.output_dir.empty()) options.output_dir = o.output_dir;
  if (o.record) options.record = true;
  if (o.start_unknown) options.start_unknown = true;
  if (o.domain_id) options.dds.domain_id = *o.domain_id;
  if (!o.participant_profile.empty()) options.dds.participant_profile = o.participant_profile;
  if (!o.security_dir.empty()) options.dds.security_dir = o.security_dir;
  if (!o.profiles_files.empty()) {
    options.dds.profiles_files.assign(o.profiles_files.begin(), o.profiles_files.end());
  }
  if (o.wait_for_readers_s) options.wait_for_readers_s = *o.wait_for_readers_s;
  if (o.linger_s) options.linger_s = *o.linger_s;
  if (o.await_corrections_s) options.await_corrections_s = *o.await_corrections_s;
  if (!o.hold_at_s.empty()) options.hold_at_s = o.hold_at_s;
  if (o.correction_max_chi2) options.corrections.max_chi2 = *o.correction_max_chi2;
  if (!o.log_level.empty()) options.log_level = o.log_level;
  pena::services::ValidateEntityOptions(options);
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-entity: the PeNa service of one firefighter or robot");
  Overrides overrides;
  AddOptions(app, overrides);
  CLI11_PARSE(app, argc, argv);
  EntityServiceOptions options;
  const auto build = [&] {
    options = BuildOptions(overrides);
    return pena::services::DaemonLogging{options.log_level, options.log_file};
  };
  return pena::services::RunDaemon("pena-entity", build, [&] {
    try {
      pena::services::EntityService service(std::move(options));
      const pena::services::EntityRunSummary summary = service.Run();
      spdlog::info("{}: {} records, {} poses, {} deltas, {} reference scans, {} snapshots sent, "
                   "{} send failures; {} corrections, {} global deltas received; line map version "
                   "{} with {} segments{}",
                   summary.entity_id, summary.records, summary.poses_sent, summary.deltas_sent,
                   summary.reference_scans_sent, summary.snapshots_sent, summary.send_failures,
                   summary.corrections_received, summary.global_deltas_received,
                   summary.local_map_version, summary.local_map_segments,
                   summary.interrupted ? " (stopped by a signal)" : "");
      if (summary.corrections_out_of_sequence + summary.corrections_held + summary.global_maps_refused > 0) {
        spdlog::warn("{}: {} corrections dropped out of sequence, {} held beyond the entity's "
                     "uncertainty; {} global map samples of another map id refused",
                     summary.entity_id, summary.corrections_out_of_sequence, summary.corrections_held,
                     summary.global_maps_refused);
      }
      if (summary.answers_awaited > 0) {
        spdlog::info("{}: lockstep: {} answers awaited, {} not received in time", summary.entity_id,
                     summary.answers_awaited, summary.answers_missed);
      }
    } catch (const pena::io::InputError& error) {
      // A signal while the live input waits for its first record ends the stream with nothing
      // read: a clean stop, as a signal is at any later point.
      if (!pena::services::StopRequested()) throw;
      spdlog::info("stopped by a signal before the first record ({})", error.what());
    }
    return EXIT_SUCCESS;
  });
}
