#pragma once
// The native PeNa mission log: a versioned, streaming, compact Protobuf record stream
// (schema idl/pena_log.proto, layout in docs/mission-log.md). One file per entity.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "pena/io/log_source.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/sensors/record.hpp"

namespace pena::io {

inline constexpr std::uint32_t kMissionLogFormatVersion = 1;

// Written once at the start of a log.
struct MissionLogHeader {
  std::uint32_t format_version = kMissionLogFormatVersion;
  std::string mission;    // scenario or recording name
  std::string entity_id;  // e.g. "ff1", "robot1"
  sensors::EntityKind kind = sensors::EntityKind::kHuman;
  sensors::LaserGeometry laser;
  double laser_height_m = 0.0;  // mounting height above the floor
  std::string producer;         // e.g. "pena simulate --scenario office --seed 1"
};

// Appends records to a new file. Throws std::runtime_error naming the path on I/O failure.
class MissionLogWriter {
 public:
  MissionLogWriter(const std::filesystem::path& path, const MissionLogHeader& header);
  ~MissionLogWriter();
  MissionLogWriter(const MissionLogWriter&) = delete;
  MissionLogWriter& operator=(const MissionLogWriter&) = delete;

  void Write(const sensors::SensorRecord& record);
  // Flushes and closes; the destructor does it too but cannot report failure.
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Reads a native log. Throws InputError (with the record index as position) on a bad magic,
// an unknown format version, a truncated or corrupt record.
class MissionLogReader : public LogSource {
 public:
  explicit MissionLogReader(const std::filesystem::path& path);
  ~MissionLogReader() override;

  const MissionLogHeader& header() const;
  std::optional<sensors::SensorRecord> Next() override;
  const LogDescription& description() const override;
  std::size_t skipped() const override { return 0; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// True if the file starts with the native log's magic bytes.
bool IsMissionLog(const std::filesystem::path& path);

}  // namespace pena::io
