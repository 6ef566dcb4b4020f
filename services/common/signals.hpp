#pragma once
// SIGINT/SIGTERM -> a stop flag the worker loop polls (the handler only stores an atomic).

namespace pena::services {

// Installs the handlers (idempotent). After a signal StopRequested() is true; a second signal
// while stopping leaves the default action (the process ends at once).
void InstallStopSignals();
// True once SIGINT or SIGTERM arrived (or RequestStop was called).
bool StopRequested();
// Sets the flag from code (tests, fatal errors in a listener).
void RequestStop();
// The signal that asked to stop (0 if none).
int StopSignal();

}  // namespace pena::services
