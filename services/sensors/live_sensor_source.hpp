#pragma once
// A LogSource fed by the live sensor topics (docs/services.md, "Live sensor input"): DDS readers
// whose listeners only enqueue, and a Next() that validates each sample (sensor_from_dds), drops
// other entities' samples, merges the topics in stamp order (SensorMerger) and ends on the
// end-of-stream marker, a stop signal or an idle timeout.

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>

#include "dds_endpoints.hpp"
#include "pena/io/log_source.hpp"
#include "pena_dds/sensorsPubSubTypes.h"
#include "sensor_merger.hpp"
#include "seq_gaps.hpp"
#include "work_queue.hpp"

namespace pena::services {

// The --input value that selects this source.
inline constexpr const char* kLiveInput = "dds";

// Options of the live input; validated by the constructor (std::invalid_argument naming the key).
struct LiveSensorOptions {
  std::string entity_id;              // samples of other entities are ignored; required
  SensorMergerOptions merge;          // reorder_window_s, sensor seconds
  // End when no sample for this entity arrived for this many wall seconds (counted from the
  // start, then from the last sample). 0: wait until the end marker or a signal.
  double idle_timeout_s = 0.0;
  // After the end marker: wait at most this long (wall seconds) for samples it counts that have
  // not arrived yet (another topic may still be delivering). > 0.
  double end_grace_s = 2.0;
};

// Throws std::invalid_argument naming the key (live_input.reorder_window_s, ...) and its unit.
void ValidateLiveSensorOptions(const LiveSensorOptions& options);

// What the live input took, per topic (index SensorTopic).
struct LiveInputCounts {
  std::array<std::size_t, kSensorTopicCount> received{};  // samples for this entity
  std::array<std::size_t, kSensorTopicCount> refused{};   // failed validation
  std::array<std::size_t, kSensorTopicCount> late{};      // older than what was released
  std::size_t released = 0;
  std::size_t bad_ranges = 0;    // NaN or negative ranges made no-returns
  SeqGapCounts gaps;             // publisher numbers that never arrived (set when the input ends)
};

class LiveSensorSource : public io::LogSource {
 public:
  // Creates the readers on `participant` (DdsError); the participant must outlive this source.
  LiveSensorSource(Participant& participant, LiveSensorOptions options);
  ~LiveSensorSource() override;

  // The next record in stamp order; nullopt once the stream ended (marker, timeout, signal).
  std::optional<sensors::SensorRecord> Next() override;
  const io::LogDescription& description() const override { return description_; }
  // Samples refused or too late.
  std::size_t skipped() const override;

  // Called about every 50 ms while Next() waits (the entity handles its inbox there).
  void SetWaitHook(std::function<void()> hook) { wait_hook_ = std::move(hook); }
  const LiveInputCounts& counts() const { return counts_; }
  // Why the stream ended: "end marker", "idle timeout", "signal" (empty while running).
  const std::string& end_reason() const { return end_reason_; }

 private:
  using Item = std::variant<pena_dds::LaserScanSample, pena_dds::GyroSample,
                            pena_dds::CompassSample, pena_dds::StrideSample,
                            pena_dds::WheelOdometrySample, pena_dds::SensorStreamStatus>;

  // Listener threads: queues a sample of this entity, counts and drops the others'.
  template <class Sample>
  void Enqueue(Sample&& sample);
  // Takes one queued sample (this entity's: Enqueue dropped the others).
  void Take(Item item);
  template <class Sample>
  void TakeSample(const Sample& sample, SensorTopic topic);
  void TakeStatus(const pena_dds::SensorStreamStatus& status);
  void Offer(TopicRecord record);
  // Ends once the marker's counts arrived or its grace passed, or the idle timeout passed.
  void CheckEnd(std::int64_t now_ns);
  void End(const std::string& reason);
  void LogSummary() const;

  LiveSensorOptions options_;
  io::LogDescription description_;
  SensorMerger merger_;
  SeqGaps seq_gaps_;
  LiveInputCounts counts_;
  std::function<void()> wait_hook_;
  std::optional<pena_dds::SensorStreamStatus> end_marker_;
  std::int64_t end_deadline_ns_ = 0;
  std::int64_t last_sample_ns_ = 0;
  bool started_ = false;  // a STARTED marker was taken
  bool ended_ = false;
  std::string end_reason_;

  std::atomic<std::size_t> other_entity_{0};  // other entities' samples, dropped by Enqueue
  WorkQueue<Item> queue_;
  Reader<pena_dds::LaserScanSamplePubSubType> scan_reader_;
  Reader<pena_dds::GyroSamplePubSubType> gyro_reader_;
  Reader<pena_dds::CompassSamplePubSubType> compass_reader_;
  Reader<pena_dds::StrideSamplePubSubType> stride_reader_;
  Reader<pena_dds::WheelOdometrySamplePubSubType> wheel_reader_;
  Reader<pena_dds::SensorStreamStatusPubSubType> status_reader_;
};

}  // namespace pena::services
