#pragma once
// A sensor log of any supported format, read as one stream of records in file order.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::io {

// How strictly to read. Defaults are strict: the first malformed line throws InputError.
struct ReadOptions {
  // Skip malformed lines (counted in LogSource::skipped()) instead of throwing.
  bool skip_malformed = false;
  // CARMEN ranges at or above this are no-returns (FLASER does not state it; docs/formats.md).
  double carmen_max_range_m = 50.0;
  // CARMEN FLASER lines with 180 beams: true spreads them over 180 deg (180/179 deg steps),
  // false uses 1 deg steps from -90 deg. docs/evaluation.md shows 1 deg fits.
  bool carmen_180_beams_span_180_deg = false;
  // Sweep time given to CARMEN scans (SICK LMS 2xx: 1/150 s; 0: every beam at the stamp), s.
  double carmen_sweep_s = 1.0 / 150.0;
  // Sweeps interleaved into one CARMEN scan (LaserGeometry::interlace). 0: from the beam spacing,
  // as a SICK LMS 2xx takes finer steps than 1 deg: 0.5 deg in 2 turns, 0.25 deg in 4.
  int carmen_interlace = 0;
};

// What a log says about itself.
struct LogDescription {
  std::filesystem::path path;
  std::string format;     // "carmen" or "pena-log"
  std::string entity_id;  // empty where the format does not name it
  std::optional<sensors::EntityKind> kind;
  std::string mission;    // scenario name for simulated logs
};

// A forward-only stream of records. Next() throws InputError on malformed input (unless skipping),
// and on time going backwards within one sensor (records already returned stay valid).
class LogSource {
 public:
  virtual ~LogSource() = default;
  // The next record, or nullopt at the end of the log.
  virtual std::optional<sensors::SensorRecord> Next() = 0;
  virtual const LogDescription& description() const = 0;
  // Malformed lines skipped so far under ReadOptions::skip_malformed.
  virtual std::size_t skipped() const = 0;
};

// Opens a CARMEN log (.clf/.log, plain or gzip) or a native PeNa log, chosen by content.
// Throws InputError if the file cannot be opened or its format is not recognised.
std::unique_ptr<LogSource> OpenLog(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace pena::io
