#pragma once
// Optional recording of what a daemon received and sent, one file per stream in a directory:
// the sensor records it consumed as a native mission log ("sensors.penalog", io::MissionLogWriter,
// docs/mission-log.md: `pena info` and every log reader open it); line-map deltas and snapshots
// as length-prefixed records in the gateway's wire encoding (io::EncodeDelta / EncodeSnapshot,
// idl/line_map.proto): "<stream>.pbs"; everything else as CSV lines: "<stream>.csv". The native
// format has no record type for DDS samples (idl/pena_log.proto), hence the other files. Layout
// in docs/services.md.

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "pena/io/mission_log.hpp"
#include "pena/line_map/map_delta.hpp"
#include "pena/sensors/record.hpp"

namespace pena::services {

class Recorder {
 public:
  // Creates `directory`; throws std::runtime_error naming it if that fails.
  explicit Recorder(const std::filesystem::path& directory);

  // Starts `directory`/sensors.penalog (throws std::invalid_argument or std::runtime_error
  // naming the path, as io::MissionLogWriter).
  void OpenSensorLog(const io::MissionLogHeader& header);
  // Appends one sensor record to sensors.penalog (no-op before OpenSensorLog); throws
  // std::invalid_argument for a record the format refuses (stamp going back in time).
  void Sensor(const sensors::SensorRecord& record);
  // Appends a delta: 'D', uint32 little-endian size, EncodeDelta bytes.
  void Delta(const std::string& stream, const line_map::MapDelta& delta);
  // Appends a snapshot: 'S', uint32 little-endian size, EncodeSnapshot bytes.
  void Snapshot(const std::string& stream, const line_map::MapSnapshot& snapshot);
  // Appends one CSV line; `header` is written first when the file is new.
  void Csv(const std::string& stream, const std::string& header, const std::string& line);
  // Flushes every file.
  void Flush();
  // Flushes and closes everything; reports a failed close of sensors.penalog (runtime_error).
  void Close();

 private:
  std::ofstream& Open(const std::string& name, bool* created);
  void Framed(const std::string& stream, char tag, const std::string& bytes);

  std::filesystem::path directory_;
  std::map<std::string, std::ofstream> files_;
  std::unique_ptr<io::MissionLogWriter> sensor_log_;
};

}  // namespace pena::services
