#pragma once
// pena-sensor-replay's application class: publishes a sensor log on the live sensor topics
// (idl/dds/sensors.idl) at a chosen rate, framed by the start and end-of-stream markers, so a
// `pena-entity --input dds` takes it as if the sensors were live (docs/services.md).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "pena/io/log_source.hpp"
#include "pena/sensors/entity.hpp"
#include "pena_dds/sensorsPubSubTypes.h"

namespace pena::services {

struct SensorReplayOptions {
  std::filesystem::path input;              // native log (or its entity directory) or CARMEN log
  std::string entity_id;                    // empty: the log's own, else the file's stem
  std::optional<sensors::EntityKind> kind;  // announced kind; empty: the log's own, else robot
  double rate = 1.0;                        // time scale; 0 = flat out (acknowledged in bursts)
  double wait_for_readers_s = 10.0;         // wall seconds to wait for a reader on every topic
  double linger_s = 5.0;                    // wall seconds to wait for acknowledgements
  DdsOptions dds;
  std::string log_level = "info";
};

// Throws std::invalid_argument naming the option and its unit.
void ValidateSensorReplayOptions(const SensorReplayOptions& options);

// What a replay published.
struct SensorReplaySummary {
  std::string entity_id;
  std::array<std::uint64_t, 5> published{};  // per SensorTopic up to kWheelOdometry
  std::uint64_t skipped_truth = 0;           // ground-truth records (no topic carries them)
  std::uint64_t refused = 0;                 // samples the middleware refused
  bool interrupted = false;
};

class SensorReplay {
 public:
  // Opens the log (io::InputError) and creates the writers (DdsError).
  explicit SensorReplay(SensorReplayOptions options);
  ~SensorReplay();
  SensorReplay(const SensorReplay&) = delete;
  SensorReplay& operator=(const SensorReplay&) = delete;

  // Publishes the whole log (or until a stop signal), then the end marker.
  SensorReplaySummary Run();

 private:
  void ReadAhead();
  void WaitForReaders();
  void PublishStarted();
  void Publish(const sensors::SensorRecord& record);
  void PublishEnded(double last_stamp_s);
  // Flat out: waits for acknowledgements every half history so keep-last never overwrites an
  // unacknowledged sample.
  template <class W>
  void Throttle(W& writer, std::uint64_t published, std::uint64_t half_depth);

  SensorReplayOptions options_;
  std::unique_ptr<io::LogSource> source_;
  std::vector<sensors::SensorRecord> read_ahead_;
  std::string entity_id_;
  sensors::EntityKind kind_ = sensors::EntityKind::kRobot;
  std::uint64_t seq_ = 0;
  SensorReplaySummary summary_;

  Participant participant_;
  Writer<pena_dds::LaserScanSamplePubSubType> scan_writer_;
  Writer<pena_dds::GyroSamplePubSubType> gyro_writer_;
  Writer<pena_dds::CompassSamplePubSubType> compass_writer_;
  Writer<pena_dds::StrideSamplePubSubType> stride_writer_;
  Writer<pena_dds::WheelOdometrySamplePubSubType> wheel_writer_;
  Writer<pena_dds::SensorStreamStatusPubSubType> status_writer_;
};

}  // namespace pena::services
