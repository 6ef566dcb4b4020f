// pena-sensor-replay: publishes a sensor log on the live sensor topics (docs/services.md, "Live
// sensor input") for a `pena-entity --input dds`. Exits 0 when the log was published (or a signal
// stopped it; the end marker goes out either way), 1 on bad options or input, 2 on a DDS failure.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdlib>

#include "daemon_main.hpp"
#include "sensor_replay.hpp"
#include "signals.hpp"

namespace {

using pena::services::SensorReplayOptions;

struct Arguments {
  std::string input, entity_id, kind, participant_profile, log_level = "info";
  std::vector<std::string> profiles_files;
  std::string security_dir;
  double rate = 1.0, wait_for_readers_s = 10.0, linger_s = 5.0;
  int domain_id = 0;
};

void AddOptions(CLI::App& app, Arguments& a) {
  app.add_option("--input", a.input, "sensors.penalog, its entity directory, or a CARMEN log")
      ->required();
  app.add_option("--entity-id", a.entity_id, "Entity id on the topics (default: the log's)");
  app.add_option("--kind", a.kind, "Announced kind, human or robot (default: the log's)");
  app.add_option("--rate", a.rate,
                 "Time scale: 1 real time, 10 ten times faster, 0 as fast as acknowledged");
  app.add_option("--domain", a.domain_id, "DDS domain id (0..232)");
  app.add_option("--profile", a.participant_profile, "Participant profile (default pena_loopback)");
  app.add_option("--profiles-file", a.profiles_files, "DDS XML profile file (repeatable)");
  app.add_option("--security", a.security_dir,
                 "DDS Security identity directory of the entity (deploy/security/make-identities.sh); default: none");
  app.add_option("--wait-for-readers", a.wait_for_readers_s,
                 "Wait up to this many seconds for a reader on every sensor topic");
  app.add_option("--linger", a.linger_s, "Seconds to wait for acknowledgements");
  app.add_option("--log-level", a.log_level, "trace, debug, info, warn, error");
}

SensorReplayOptions BuildOptions(const Arguments& a) {
  SensorReplayOptions options;
  options.input = a.input;
  if (std::filesystem::is_directory(options.input)) options.input /= "sensors.penalog";
  options.entity_id = a.entity_id;
  if (!a.kind.empty()) {
    options.kind = pena::sensors::ParseEntityKind(a.kind);
    if (!options.kind) throw std::invalid_argument("--kind must be human or robot");
  }
  options.rate = a.rate;
  options.wait_for_readers_s = a.wait_for_readers_s;
  options.linger_s = a.linger_s;
  options.dds.domain_id = a.domain_id;
  if (!a.participant_profile.empty()) options.dds.participant_profile = a.participant_profile;
  options.dds.security_dir = a.security_dir;
  // Secured, the sensors write in the entity's partition like the entity itself.
  options.dds.own_partition = true;
  if (a.profiles_files.empty()) {
    options.dds.profiles_files = pena::services::DefaultProfilesFiles();
  } else {
    options.dds.profiles_files.assign(a.profiles_files.begin(), a.profiles_files.end());
  }
  options.log_level = a.log_level;
  pena::services::ValidateSensorReplayOptions(options);
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-sensor-replay: publishes a sensor log on the live sensor topics");
  Arguments arguments;
  AddOptions(app, arguments);
  CLI11_PARSE(app, argc, argv);
  SensorReplayOptions options;
  const auto build = [&] {
    options = BuildOptions(arguments);
    return pena::services::DaemonLogging{options.log_level, {}};
  };
  return pena::services::RunDaemon("pena-sensor-replay", build, [&] {
    pena::services::SensorReplay replay(std::move(options));
    const pena::services::SensorReplaySummary summary = replay.Run();
    spdlog::info("{}: published {} scans, {} gyro, {} compass, {} stride, {} wheel odometry "
                 "samples and the end marker; {} ground-truth records not published, {} refused{}",
                 summary.entity_id, summary.published[0], summary.published[1],
                 summary.published[2], summary.published[3], summary.published[4],
                 summary.skipped_truth, summary.refused,
                 summary.interrupted ? " (stopped by a signal)" : "");
    return EXIT_SUCCESS;
  });
}
