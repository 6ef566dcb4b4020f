#pragma once
// Small pieces every subcommand shares: number and JSON formatting, wall-clock timing, stage
// times and peak memory for summaries, the progress line on long logs, and the rule for where a
// run over a log starts.

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/io/log_source.hpp"
#include "pena/pipeline/start_pose.hpp"
#include "pena/sensors/record.hpp"
#include "pena/stage_clock.hpp"

namespace pena::cli {

using Clock = std::chrono::steady_clock;

// `value` with `decimals` digits after the point.
std::string Fixed(double value, int decimals);

// `text` as a JSON string literal (quotes, backslashes and control characters escaped).
std::string JsonString(const std::string& text);

// Wall-clock seconds since `start`.
double SecondsSince(Clock::time_point start);

// The process's peak resident memory so far (getrusage ru_maxrss), megabytes (2^20 bytes).
double PeakResidentMb();

// {"total": {"s": S, "calls": N}, "<stage>": {...}, ...}: a chain's stage times for summary.json
// (stage names from ToString).
template <typename Stage>
std::string StageTimesJson(const StageTimes<Stage>& times) {
  const auto entry = [](const std::string& name, const StageTime& time) {
    return JsonString(name) + ": {\"s\": " + Fixed(time.seconds, 4) +
           ", \"calls\": " + std::to_string(time.calls) + "}";
  };
  std::string json = "{" + entry("total", times.total);
  for (std::size_t i = 0; i < times.stages.size(); ++i) {
    json += ", " + entry(ToString(static_cast<Stage>(i)), times.stages[i]);
  }
  return json + "}";
}

// One `--set NAME=NUMBER` setting, split and checked (a finite number, nothing after it).
struct Setting {
  std::string name;
  double value = 0.0;
};
Setting ParseSetting(const std::string& setting);

// The option fields a subcommand's --set may change, by name: numbers, integers (rounded) and
// flags (0 off, anything else on).
struct SettingTargets {
  std::map<std::string, double*> doubles;
  std::map<std::string, int*> ints;
  std::map<std::string, bool*> flags;
};
// Sets the field named `setting.name`; false (nothing changed) when no target has that name.
bool ApplySetting(const SettingTargets& targets, const Setting& setting);

// One stderr line, rewritten in place on a terminal (a plain line otherwise), at most every 2 s.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled);
  // Ends the rewritten line so later output (or an error) starts on its own line.
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // True when a line is due at `wall_s` seconds into the run.
  bool Due(double wall_s) const;
  void Show(double wall_s, const std::string& text);

 private:
  bool enabled_;
  bool terminal_;
  bool shown_ = false;
  double last_wall_s_ = 0.0;
};

// Where a run over a log starts when the user gave no start: pipeline::StartPoseOf, the rule
// pena-entity follows, for `source`'s format. `read_ahead` holds the log's first records.
using pipeline::StartPose;
StartPose StartPoseOf(const std::vector<sensors::SensorRecord>& read_ahead,
                      const io::LogSource& source);

}  // namespace pena::cli
