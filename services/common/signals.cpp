#include "signals.hpp"

#include <atomic>
#include <csignal>

namespace pena::services {
namespace {

std::atomic<int> g_stop_signal{0};
std::atomic<bool> g_stop{false};

extern "C" void OnStopSignal(int signal_number) {
  g_stop_signal.store(signal_number);
  g_stop.store(true);
  // A second Ctrl-C while shutting down should end the process: back to the default action.
  std::signal(signal_number, SIG_DFL);
}

}  // namespace

void InstallStopSignals() {
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
}

bool StopRequested() { return g_stop.load(); }

void RequestStop() { g_stop.store(true); }

int StopSignal() { return g_stop_signal.load(); }

}  // namespace pena::services
