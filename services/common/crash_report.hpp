#pragma once
// A daemon that crashes (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) writes the signal and a
// backtrace to stderr before it dies, so a crash seen once in a test or in the field leaves
// something to read. The process still dies of the same signal (exit status 128 + N, a core
// dump where enabled). Frames in the executable are printed as `pena-entity(+0x1f2e3)`:
// `addr2line -f -C -e pena-entity 0x1f2e3` names the function and line.

#include <string>

namespace pena::services {

// Installs the handlers; `program` is printed with the report (its first 63 characters are
// copied). Idempotent.
void InstallCrashReport(const std::string& program);

}  // namespace pena::services
