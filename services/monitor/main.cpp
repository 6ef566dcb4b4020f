// pena-monitor: the command post's passive view of a PeNa DDS domain for the link experiments
// (docs/link-experiments.md). Logs pose ages and the global map's state to CSV until the
// duration passed or SIGINT/SIGTERM, then writes the final global map. `--digest FILE` prints
// the map digest of a line CSV (e.g. pena-fusion's global_map.csv) and exits.
// Exits 0 on success, 1 on bad options or input, 2 on a DDS failure.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>

#include "crash_report.hpp"
#include "logging.hpp"
#include "map_digest.hpp"
#include "monitor_service.hpp"
#include "pena/io/line_csv.hpp"
#include "signals.hpp"

int main(int argc, char** argv) {
  CLI::App app("pena-monitor: pose age and global-map state at the command post");
  pena::services::MonitorOptions options;
  std::string output_dir, participant_profile, digest_file, log_level = "info";
  std::vector<std::string> profiles_files;
  std::string security_dir;
  app.add_option("--out", output_dir, "Output directory: poses.csv, map.csv, global_map.csv");
  app.add_option("--duration", options.duration_s, "Wall seconds to run (0: until a signal)");
  app.add_option("--domain", options.dds.domain_id, "DDS domain id (0..232)");
  app.add_option("--profile", participant_profile, "Participant profile (default pena_loopback)");
  app.add_option("--profiles-file", profiles_files, "DDS XML profile file (repeatable)");
  app.add_option("--security", security_dir,
                 "DDS Security identity directory (deploy/security/make-identities.sh); default: none, an open participant");
  app.add_option("--digest", digest_file, "Print the map digest of this line CSV and exit");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!digest_file.empty()) {
      const auto rows = pena::io::ReadLineCsv(digest_file);
      std::cout << pena::services::DigestHex(pena::services::MapDigest(rows)) << ' ' << rows.size()
                << '\n';
      return EXIT_SUCCESS;
    }
    pena::services::SetupLogging("pena-monitor", log_level, {});
    options.output_dir = output_dir;
    if (!participant_profile.empty()) options.dds.participant_profile = participant_profile;
    options.dds.security_dir = security_dir;
    options.dds.profiles_files =
        profiles_files.empty()
            ? pena::services::DefaultProfilesFiles()
            : std::vector<std::filesystem::path>(profiles_files.begin(), profiles_files.end());
    pena::services::ValidateMonitorOptions(options);
  } catch (const std::exception& error) {
    std::cerr << "pena-monitor: " << error.what() << '\n';
    return EXIT_FAILURE;
  }
  pena::services::InstallStopSignals();
  pena::services::InstallCrashReport("pena-monitor");
  try {
    pena::services::MonitorService service(std::move(options));
    const pena::services::MonitorSummary summary = service.Run();
    spdlog::info("{} poses ({} missing), {} deltas applied, map version {} with {} segments",
                 summary.poses, summary.poses_missing, summary.deltas_applied, summary.map_version,
                 summary.map_segments);
  } catch (const pena::services::DdsError& error) {
    std::cerr << "pena-monitor: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "pena-monitor: " << error.what() << '\n';
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
