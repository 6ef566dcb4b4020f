#pragma once
// What a sensor log holds, summarised from one pass over it (`pena info`).

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <variant>

#include "pena/io/log_source.hpp"
#include "pena/sensors/record.hpp"

namespace pena::io {

// Number of sensor kinds: the alternatives of sensors::SensorRecord.
inline constexpr std::size_t kSensorKindCount = std::variant_size_v<sensors::SensorRecord>;

// Short name of the sensor behind SensorRecord alternative `index` ("laser", "gyro", ...).
std::string_view SensorName(std::size_t index);

// Count and time range of one stream (stamps in seconds; zero when count is 0).
struct StreamSummary {
  std::size_t count = 0;
  double first_stamp_s = 0.0;
  double last_stamp_s = 0.0;
  // last_stamp_s - first_stamp_s, seconds.
  double duration_s() const { return last_stamp_s - first_stamp_s; }
};

// Beam statistics over all laser scans (zero when there are none).
struct LaserSummary {
  std::size_t min_beams = 0;      // fewest beams in one scan
  std::size_t max_beams = 0;      // most beams in one scan
  double angle_min_rad = 0.0;     // first beam angle, smallest over scans (laser frame)
  double angle_max_rad = 0.0;     // last beam angle, largest over scans (laser frame)
  double max_range_m = 0.0;       // largest sensor maximum range of any scan
  double longest_return_m = 0.0;  // longest usable range measured
  std::size_t beams = 0;          // beams in all scans
  std::size_t no_returns = 0;     // beams without a usable range
  // no_returns / beams, 0 when there are no beams.
  double no_return_fraction() const;
};

// One pass over a log: who recorded it, what each sensor stream holds, how the scans look.
struct LogSummary {
  LogDescription description;                           // path, format, entity id, kind, mission
  std::array<StreamSummary, kSensorKindCount> sensors;  // indexed like sensors::SensorRecord
  StreamSummary overall;                                // all records: earliest and latest stamp
  LaserSummary laser;
  std::size_t skipped_lines = 0;  // malformed lines skipped by the reader (ReadOptions)
};

// Reads `source` to its end. Throws whatever the source throws (InputError on bad input).
LogSummary SummarizeLog(LogSource& source);

// A readable multi-line block (like `ros2 bag info`), ending with a newline.
std::string FormatSummary(const LogSummary& summary);

}  // namespace pena::io
