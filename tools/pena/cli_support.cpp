#include "cli_support.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace pena::cli {

std::string Fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

double PeakResidentMb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

Setting ParseSetting(const std::string& setting) {
  const std::size_t equals = setting.find('=');
  char* end = nullptr;
  const double value =
      equals == std::string::npos ? NAN : std::strtod(setting.c_str() + equals + 1, &end);
  if (!std::isfinite(value) || end == nullptr || *end != '\0') {
    throw std::runtime_error("--set: expected NAME=NUMBER, got '" + setting + "'");
  }
  return {setting.substr(0, equals), value};
}

bool ApplySetting(const SettingTargets& targets, const Setting& setting) {
  if (const auto d = targets.doubles.find(setting.name); d != targets.doubles.end()) {
    *d->second = setting.value;
  } else if (const auto i = targets.ints.find(setting.name); i != targets.ints.end()) {
    *i->second = static_cast<int>(std::lround(setting.value));
  } else if (const auto f = targets.flags.find(setting.name); f != targets.flags.end()) {
    *f->second = setting.value != 0.0;
  } else {
    return false;
  }
  return true;
}

std::string JsonString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled), terminal_(isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() {
  if (shown_ && terminal_) std::fputc('\n', stderr);
}

bool ProgressLine::Due(double wall_s) const { return enabled_ && wall_s >= last_wall_s_ + 2.0; }

void ProgressLine::Show(double wall_s, const std::string& text) {
  last_wall_s_ = wall_s;
  shown_ = true;
  std::fprintf(stderr, "%s%s%s", terminal_ ? "\r" : "", text.c_str(), terminal_ ? "" : "\n");
  std::fflush(stderr);
}

StartPose StartPoseOf(const std::vector<sensors::SensorRecord>& read_ahead,
                      const io::LogSource& source) {
  return pipeline::StartPoseOf(read_ahead, source.description().format == "pena-log");
}

}  // namespace pena::cli
