#include "daemon_main.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <exception>
#include <iostream>

#include "crash_report.hpp"
#include "dds_participant.hpp"
#include "logging.hpp"
#include "signals.hpp"

namespace pena::services {

int RunDaemon(const std::string& name, const std::function<DaemonLogging()>& build,
              const std::function<int()>& run) {
  try {
    const DaemonLogging logging = build();
    SetupLogging(name, logging.level, logging.file);
  } catch (const std::exception& error) {
    std::cerr << name << ": " << error.what() << '\n';
    return EXIT_FAILURE;
  }
  InstallStopSignals();
  InstallCrashReport(name);
  try {
    return run();
  } catch (const DdsError& error) {
    spdlog::critical("DDS failure: {}", error.what());
    return 2;
  } catch (const std::exception& error) {
    spdlog::critical("{}", error.what());
    return EXIT_FAILURE;
  }
}

}  // namespace pena::services
