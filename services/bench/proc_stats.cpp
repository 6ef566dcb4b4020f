#include "proc_stats.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace pena::services::bench {

std::optional<ProcSample> ReadProc(pid_t pid) {
  const std::string dir = "/proc/" + std::to_string(pid) + "/";
  std::ifstream stat(dir + "stat");
  std::string line;
  if (!std::getline(stat, line)) return std::nullopt;
  // Fields after the command name (in parentheses, may hold spaces): state is field 3, utime 14,
  // stime 15 (proc(5)).
  const std::size_t close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  double utime = 0.0, stime = 0.0;
  for (int index = 3; index <= 15 && fields >> field; ++index) {
    if (index == 14) utime = std::stod(field);
    if (index == 15) stime = std::stod(field);
  }
  ProcSample sample;
  sample.cpu_s = (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
  std::ifstream status(dir + "status");
  while (std::getline(status, line)) {
    std::istringstream words(line);
    std::string key;
    std::int64_t kb = 0;
    words >> key >> kb;
    if (key == "VmRSS:") sample.rss_kb = kb;
    if (key == "VmHWM:") sample.hwm_kb = kb;
  }
  return sample;
}

double SelfCpuS() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(q * static_cast<double>(values.size()));
  const auto index = static_cast<std::size_t>(std::max(rank, 1.0)) - 1;
  return values[std::min(index, values.size() - 1)];
}

}  // namespace pena::services::bench
