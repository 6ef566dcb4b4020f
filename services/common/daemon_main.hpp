#pragma once
// The shape every PeNa daemon's main has (pena-entity, pena-fusion, pena-sensor-replay): build
// the options and set up logging, install the stop signals, run, and map failures to exit codes.

#include <filesystem>
#include <functional>
#include <string>

namespace pena::services {

// What `build` hands back for the logging set-up.
struct DaemonLogging {
  std::string level;
  std::filesystem::path file;  // empty: stderr only
};

// Calls `build` (bad options or logging: "<name>: what" on stderr, EXIT_FAILURE), installs the
// stop signals and the crash report and returns what `run` returns; a DdsError escaping `run`
// exits 2, any other exception EXIT_FAILURE, both logged as critical.
int RunDaemon(const std::string& name, const std::function<DaemonLogging()>& build,
              const std::function<int()>& run);

}  // namespace pena::services
