#include "sensor_replay.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "pena/io/input_error.hpp"
#include "pena/pipeline/start_pose.hpp"
#include "log_start.hpp"
#include "sensor_merger.hpp"
#include "sensor_to_dds.hpp"
#include "sensor_topics.hpp"
#include "signals.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

std::int64_t SecondsToNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

std::size_t Index(SensorTopic topic) { return static_cast<std::size_t>(topic); }

}  // namespace

void ValidateSensorReplayOptions(const SensorReplayOptions& options) {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  require(!options.input.empty(), "--input is required (a sensors.penalog or a CARMEN log)");
  require(std::isfinite(options.rate) && options.rate >= 0.0,
          "--rate must be >= 0 (0 = as fast as acknowledged), got " + std::to_string(options.rate));
  require(std::isfinite(options.wait_for_readers_s) && options.wait_for_readers_s >= 0.0,
          "--wait-for-readers must be >= 0 s, got " + std::to_string(options.wait_for_readers_s));
  require(std::isfinite(options.linger_s) && options.linger_s >= 0.0,
          "--linger must be >= 0 s, got " + std::to_string(options.linger_s));
  require(options.dds.domain_id >= 0 && options.dds.domain_id <= 232,
          "--domain must be in 0..232, got " + std::to_string(options.dds.domain_id));
}

SensorReplay::SensorReplay(SensorReplayOptions options)
    : options_(std::move(options)),
      source_(io::OpenLog(options_.input)),
      participant_(options_.dds, "pena-sensor-replay"),
      scan_writer_(participant_, topics::kSensorScan),
      gyro_writer_(participant_, topics::kSensorGyro),
      compass_writer_(participant_, topics::kSensorCompass),
      stride_writer_(participant_, topics::kSensorStride),
      wheel_writer_(participant_, topics::kSensorWheelOdometry),
      status_writer_(participant_, topics::kSensorStatus) {
  ReadAhead();
}

SensorReplay::~SensorReplay() = default;

void SensorReplay::ReadAhead() {
  // Up to the first scan: the start pose comes from there, exactly as pena-entity takes it.
  LogStart log_start = ReadLogStart(*source_, options_.input, options_.entity_id, options_.kind);
  read_ahead_ = std::move(log_start.records);
  if (read_ahead_.empty()) throw io::InputError(options_.input, 0, "the log holds no records");
  kind_ = log_start.kind;
  entity_id_ = std::move(log_start.entity_id);
  summary_.entity_id = entity_id_;
}

void SensorReplay::WaitForReaders() {
  if (options_.wait_for_readers_s <= 0.0) return;
  const std::int64_t until_ns = NowNs() + SecondsToNs(options_.wait_for_readers_s);
  auto all_matched = [this] {
    return scan_writer_.matched() > 0 && gyro_writer_.matched() > 0 &&
           compass_writer_.matched() > 0 && stride_writer_.matched() > 0 &&
           wheel_writer_.matched() > 0 && status_writer_.matched() > 0;
  };
  while (!all_matched() && NowNs() < until_ns && !StopRequested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!all_matched()) {
    spdlog::warn("{}: not every sensor topic has a reader after {} s; publishing anyway",
                 entity_id_, options_.wait_for_readers_s);
  }
}

void SensorReplay::PublishStarted() {
  const io::LogDescription& description = source_->description();
  const pipeline::StartPose start =
      pipeline::StartPoseOf(read_ahead_, description.format == "pena-log");
  pena_dds::SensorStreamStatus status;
  SetBounded(status.entity_id(), entity_id_, "entity_id");
  status.schema_version(pena_dds::SCHEMA_VERSION);
  status.state(pena_dds::SENSORS_STARTED);
  status.kind(ToDds(kind_));
  status.mission(description.mission.substr(0, 64));
  status.stamp_s(sensors::StampOf(read_ahead_.front()));
  // Only the mission's known start (ground truth before the first scan) is announced; a scan's
  // odometry pose travels with the scan and the entity takes it from there.
  status.start_pose_known(start.source == "ground truth");
  status.world_from_body_start(ToDds(start.world_from_body));
  if (!status_writer_.Write(status)) ++summary_.refused;
  // The start pose must be in the reader before the first record it precedes.
  status_writer_.WaitForAcknowledgments(options_.linger_s);
  spdlog::info("{}: replaying {} ({}) at rate {}; start pose from {}", entity_id_,
               options_.input.string(), sensors::ToString(kind_), options_.rate, start.source);
}

SensorReplaySummary SensorReplay::Run() {
  WaitForReaders();
  PublishStarted();
  const double first_stamp_s = sensors::StampOf(read_ahead_.front());
  const std::int64_t wall_start_ns = NowNs();
  double last_stamp_s = first_stamp_s;
  std::size_t ahead = 0;
  while (!StopRequested()) {
    std::optional<sensors::SensorRecord> record = NextRecord(read_ahead_, ahead, *source_);
    if (!record) break;
    last_stamp_s = sensors::StampOf(*record);
    if (options_.rate > 0.0) {
      const std::int64_t due_ns =
          wall_start_ns + SecondsToNs((last_stamp_s - first_stamp_s) / options_.rate);
      while (NowNs() < due_ns && !StopRequested()) {
        std::this_thread::sleep_for(std::chrono::nanoseconds(
            std::min<std::int64_t>(due_ns - NowNs(), 50'000'000)));
      }
    }
    Publish(*record);
  }
  summary_.interrupted = StopRequested();
  PublishEnded(last_stamp_s);
  return summary_;
}

template <class W>
void SensorReplay::Throttle(W& writer, std::uint64_t published, std::uint64_t half_depth) {
  if (options_.rate > 0.0 || half_depth == 0 || published % half_depth != 0) return;
  if (!writer.WaitForAcknowledgments(options_.linger_s)) {
    spdlog::warn("{}: {} not acknowledged within {} s; keep-last may overwrite samples",
                 entity_id_, writer.topic_name(), options_.linger_s);
  }
}

void SensorReplay::Publish(const sensors::SensorRecord& record) {
  SensorSample sample = ToDdsSensorSample(record, entity_id_, seq_ + 1);
  auto send = [this](auto& writer, auto& dds_sample, SensorTopic topic) {
    ++seq_;
    if (!writer.Write(dds_sample)) {
      ++summary_.refused;
      spdlog::warn("{}: DDS refused sample seq {} on {}", entity_id_, seq_, writer.topic_name());
      return;
    }
    const std::uint64_t published = ++summary_.published[Index(topic)];
    Throttle(writer, published, static_cast<std::uint64_t>(writer.history_depth() / 2));
  };
  if (auto* scan = std::get_if<pena_dds::LaserScanSample>(&sample)) {
    send(scan_writer_, *scan, SensorTopic::kScan);
  } else if (auto* gyro = std::get_if<pena_dds::GyroSample>(&sample)) {
    send(gyro_writer_, *gyro, SensorTopic::kGyro);
  } else if (auto* compass = std::get_if<pena_dds::CompassSample>(&sample)) {
    send(compass_writer_, *compass, SensorTopic::kCompass);
  } else if (auto* stride = std::get_if<pena_dds::StrideSample>(&sample)) {
    send(stride_writer_, *stride, SensorTopic::kStride);
  } else if (auto* wheel = std::get_if<pena_dds::WheelOdometrySample>(&sample)) {
    send(wheel_writer_, *wheel, SensorTopic::kWheelOdometry);
  } else {
    ++summary_.skipped_truth;
  }
}

void SensorReplay::PublishEnded(double last_stamp_s) {
  // Every sample is in the readers before the marker that counts them goes out.
  const bool acknowledged = scan_writer_.WaitForAcknowledgments(options_.linger_s) &&
                            gyro_writer_.WaitForAcknowledgments(options_.linger_s) &&
                            compass_writer_.WaitForAcknowledgments(options_.linger_s) &&
                            stride_writer_.WaitForAcknowledgments(options_.linger_s) &&
                            wheel_writer_.WaitForAcknowledgments(options_.linger_s);
  if (!acknowledged) {
    spdlog::warn("{}: not every reader acknowledged the sensor samples within {} s", entity_id_,
                 options_.linger_s);
  }
  pena_dds::SensorStreamStatus status;
  SetBounded(status.entity_id(), entity_id_, "entity_id");
  status.schema_version(pena_dds::SCHEMA_VERSION);
  status.state(pena_dds::SENSORS_ENDED);
  status.kind(ToDds(kind_));
  status.mission(source_->description().mission.substr(0, 64));
  status.stamp_s(last_stamp_s);
  status.scans(summary_.published[Index(SensorTopic::kScan)]);
  status.gyro(summary_.published[Index(SensorTopic::kGyro)]);
  status.compass(summary_.published[Index(SensorTopic::kCompass)]);
  status.stride(summary_.published[Index(SensorTopic::kStride)]);
  status.wheel_odometry(summary_.published[Index(SensorTopic::kWheelOdometry)]);
  if (!status_writer_.Write(status)) ++summary_.refused;
  if (!status_writer_.WaitForAcknowledgments(options_.linger_s)) {
    spdlog::warn("{}: the end marker was not acknowledged within {} s", entity_id_,
                 options_.linger_s);
  }
}

}  // namespace pena::services
