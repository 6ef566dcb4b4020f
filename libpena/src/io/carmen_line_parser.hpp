#pragma once
// Private: turns one CARMEN log line into a sensor record (layouts in docs/formats.md).

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "pena/io/log_source.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/sensors/record.hpp"

namespace pena::io::detail {

// What is wrong with a line; the reader adds path and line number (InputError).
class CarmenLineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A parsed line of a known message type.
struct CarmenMessage {
  std::string type;  // "FLASER", "ODOM", "ROBOTLASER1", "RAWLASER1".."RAWLASER4"
  sensors::SensorRecord record;
};

// Parses one line. nullopt for blank lines, '#' comments and message types the reader ignores;
// throws CarmenLineError for a malformed line of a known type.
std::optional<CarmenMessage> ParseCarmenLine(std::string_view line, const ReadOptions& options);

// Beam geometry of an n-beam FLASER scan (FLASER does not state it; see docs/formats.md).
sensors::LaserGeometry FlaserGeometry(std::size_t beam_count, const ReadOptions& options);
// The sweeps interleaved in a CARMEN scan of this beam spacing (ReadOptions::carmen_interlace).
int CarmenInterlace(double angle_increment_rad, const ReadOptions& options);

}  // namespace pena::io::detail
