#pragma once
// The start of a sensor stream as pena-entity and pena-sensor-replay both read it: the records up
// to the first scan (the start pose and the first stamp come from there) and who the entity is.
// One definition for both, because the replay publishes under the entity id the entity then
// looks for.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pena/io/log_source.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::services {

struct LogStart {
  std::vector<sensors::SensorRecord> records;  // up to and including the first scan
  std::string entity_id;  // given, else the log's own, else the file name up to its first '.'
  sensors::EntityKind kind = sensors::EntityKind::kRobot;  // given, else the log's own, else robot
};

// Reads `source` (opened from `input`) up to its first scan. `records` is empty if the stream
// ended before any record: the caller words that error for its input.
LogStart ReadLogStart(io::LogSource& source, const std::filesystem::path& input,
                      const std::string& entity_id, std::optional<sensors::EntityKind> kind);

// The next record of a stream whose start ReadLogStart took: first the records read ahead (moved
// out in order; `taken` counts them), then the source's own, so the service sees the stream as if
// nothing had been read ahead. Empty at the end of the stream.
std::optional<sensors::SensorRecord> NextRecord(std::vector<sensors::SensorRecord>& read_ahead,
                                                std::size_t& taken, io::LogSource& source);

}  // namespace pena::services
