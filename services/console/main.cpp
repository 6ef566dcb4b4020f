// pena-console: the command post's live view of a PeNa DDS domain in a browser
// (docs/console.md). Serves one page on 127.0.0.1:8090 by default; the operator's three-point
// rotations go out as pena_dds::OperatorCorrection, marks as pena_dds::Annotation. Runs until
// SIGINT/SIGTERM (or --duration).
// Exits 0 on success, 1 on bad options, 2 on a DDS failure.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>

#include "console_service.hpp"
#include "daemon_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("pena-console: the command post's live view in a browser");
  pena::services::ConsoleOptions o;
  std::string participant_profile, log_level = "info";
  std::vector<std::string> profiles_files;
  app.add_option("--bind", o.web.bind_address, "Address to listen on (default 127.0.0.1)");
  app.add_option("--port", o.web.port, "TCP port (default 8090; 0: any free port)");
  app.add_option("--port-file", o.port_file, "Write the port listened on to this file");
  app.add_option("--operator-id", o.operator_id,
                 "Author of this console's corrections and marks");
  app.add_option("--stale-after", o.picture.stale_after_s,
                 "Wall seconds without a pose before an entity shows as stale");
  app.add_option("--trail-points", o.picture.trail_points, "Trail points kept per entity");
  app.add_option("--tick", o.tick_s, "Wall seconds between updates to the browsers");
  app.add_option("--duration", o.duration_s, "Wall seconds to run (0: until a signal)");
  app.add_option("--domain", o.dds.domain_id, "DDS domain id (0..232)");
  app.add_option("--profile", participant_profile, "Participant profile (default pena_loopback)");
  app.add_option("--profiles-file", profiles_files, "DDS XML profile file (repeatable)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  CLI11_PARSE(app, argc, argv);
  return pena::services::RunDaemon(
      "pena-console",
      [&] {
        if (!participant_profile.empty()) o.dds.participant_profile = participant_profile;
        o.dds.profiles_files =
            profiles_files.empty()
                ? pena::services::DefaultProfilesFiles()
                : std::vector<std::filesystem::path>(profiles_files.begin(),
                                                     profiles_files.end());
        pena::services::ValidateConsoleOptions(o);
        return pena::services::DaemonLogging{log_level, {}};
      },
      [&] {
        pena::services::ConsoleService service(o);
        const std::string address = o.web.bind_address.find(':') == std::string::npos
                                        ? o.web.bind_address
                                        : "[" + o.web.bind_address + "]";
        std::printf("pena-console: open http://%s:%u/\n", address.c_str(),
                    static_cast<unsigned>(service.port()));
        std::fflush(stdout);
        const pena::services::ConsoleSummary s = service.Run();
        spdlog::info("{} samples, {} browsers, {} requests ({} refused), {} corrections sent, {} "
                     "deltas", s.samples, s.browsers, s.requests, s.refused, s.corrections_sent,
                     s.deltas_sent);
        return EXIT_SUCCESS;
      });
}
