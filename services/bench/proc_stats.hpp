#pragma once
// CPU time and memory of a process from /proc (Linux): what pena-load reports for pena-fusion.

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace pena::services::bench {

// One reading of /proc/<pid>/stat and /proc/<pid>/status.
struct ProcSample {
  double cpu_s = 0.0;        // user + system CPU seconds since the process started
  std::int64_t rss_kb = 0;   // VmRSS: resident now, kB
  std::int64_t hwm_kb = 0;   // VmHWM: peak resident so far, kB
};

// nullopt if the process is gone or /proc cannot be read.
std::optional<ProcSample> ReadProc(pid_t pid);

// User + system CPU seconds of this process (getrusage).
double SelfCpuS();

// The q-quantile (0..1, nearest rank) of `values`; 0 for none.
double Quantile(std::vector<double> values, double q);

}  // namespace pena::services::bench
