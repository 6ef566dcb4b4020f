#include "live_sensor_source.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "sensor_from_dds.hpp"
#include "sensor_topics.hpp"
#include "signals.hpp"

namespace pena::services {
namespace {

// Next() wakes at least this often to call the wait hook and look at signals and timeouts.
constexpr auto kPoll = std::chrono::milliseconds(50);
// Samples taken from the queue between two looks at the window, signals and timeouts.
constexpr int kMaxBatch = 1024;
// Wall seconds beyond which a timeout would overflow the nanosecond clock arithmetic.
constexpr double kMaxTimeoutS = 1e6;

std::int64_t SecondsToNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

// Warn about the first few problems of a kind, then every hundredth: a hostile or broken
// publisher must not flood the log, but the count is always in the message.
bool WorthLogging(std::size_t count) { return count <= 5 || count % 100 == 0; }

template <class Sample>
constexpr SensorTopic TopicOf() {
  if constexpr (std::is_same_v<Sample, pena_dds::LaserScanSample>) return SensorTopic::kScan;
  if constexpr (std::is_same_v<Sample, pena_dds::GyroSample>) return SensorTopic::kGyro;
  if constexpr (std::is_same_v<Sample, pena_dds::CompassSample>) return SensorTopic::kCompass;
  if constexpr (std::is_same_v<Sample, pena_dds::StrideSample>) return SensorTopic::kStride;
  return SensorTopic::kWheelOdometry;
}

std::size_t Index(SensorTopic topic) { return static_cast<std::size_t>(topic); }

}  // namespace

void ValidateLiveSensorOptions(const LiveSensorOptions& options) {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  require(!options.entity_id.empty(),
          "input dds needs the entity id (--entity-id or entity_id): the sensor topics carry "
          "every entity's samples");
  require(options.entity_id.size() <= 32, "entity_id holds at most 32 characters, got '" +
                                              options.entity_id + "'");
  const double window_s = options.merge.reorder_window_s;
  require(std::isfinite(window_s) && window_s >= 0.0 && window_s <= 60.0,
          "live_input.reorder_window_s must be in [0, 60] s of sensor time, got " +
              std::to_string(window_s));
  require(std::isfinite(options.idle_timeout_s) && options.idle_timeout_s >= 0.0 &&
              options.idle_timeout_s <= kMaxTimeoutS,
          "live_input.idle_timeout_s must be in [0, 1e6] s (0 = none), got " +
              std::to_string(options.idle_timeout_s));
  require(std::isfinite(options.end_grace_s) && options.end_grace_s > 0.0 &&
              options.end_grace_s <= kMaxTimeoutS,
          "live_input.end_grace_s must be in (0, 1e6] s, got " + std::to_string(options.end_grace_s));
}

LiveSensorSource::LiveSensorSource(Participant& participant, LiveSensorOptions options)
    : options_((ValidateLiveSensorOptions(options), std::move(options))),
      merger_(options_.merge),
      scan_reader_(participant, topics::kSensorScan,
                   [this](pena_dds::LaserScanSample&& s, const SampleMeta&) { Enqueue(std::move(s)); }),
      gyro_reader_(participant, topics::kSensorGyro,
                   [this](pena_dds::GyroSample&& s, const SampleMeta&) { Enqueue(std::move(s)); }),
      compass_reader_(participant, topics::kSensorCompass,
                      [this](pena_dds::CompassSample&& s, const SampleMeta&) { Enqueue(std::move(s)); }),
      stride_reader_(participant, topics::kSensorStride,
                     [this](pena_dds::StrideSample&& s, const SampleMeta&) { Enqueue(std::move(s)); }),
      wheel_reader_(participant, topics::kSensorWheelOdometry,
                    [this](pena_dds::WheelOdometrySample&& s, const SampleMeta&) {
                      Enqueue(std::move(s));
                    }),
      status_reader_(participant, topics::kSensorStatus,
                     [this](pena_dds::SensorStreamStatus&& s, const SampleMeta&) {
                       Enqueue(std::move(s));
                     }) {
  description_.path = kLiveInput;
  description_.format = kLiveInput;
  description_.entity_id = options_.entity_id;
  last_sample_ns_ = NowNs();
}

LiveSensorSource::~LiveSensorSource() = default;

template <class Sample>
void LiveSensorSource::Enqueue(Sample&& sample) {
  // Every entity's samples reach every reader (one keyed topic per sensor): drop the others on
  // the listener's thread so that a busy domain does not fill this entity's queue.
  if (sample.entity_id().to_string() != options_.entity_id) {
    other_entity_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  queue_.Push(std::forward<Sample>(sample));
}

std::size_t LiveSensorSource::skipped() const {
  std::size_t out = 0;
  for (std::size_t i = 0; i < kSensorTopicCount; ++i) out += counts_.refused[i] + counts_.late[i];
  return out;
}

std::optional<sensors::SensorRecord> LiveSensorSource::Next() {
  while (true) {
    if (std::optional<TopicRecord> ready = merger_.PopReady()) {
      ++counts_.released;
      return std::move(ready->record);
    }
    if (ended_) {
      if (std::optional<TopicRecord> rest = merger_.PopOldest()) {
        ++counts_.released;
        return std::move(rest->record);
      }
      return std::nullopt;
    }
    if (StopRequested()) {
      // The caller stops too; what is held is not worth the wait.
      End("signal");
      return std::nullopt;
    }
    if (std::optional<Item> item = queue_.PopFor(kPoll)) {
      Take(std::move(*item));
      // Take what is queued before looking at the window again, but a bounded batch: under a
      // flood the loop must still reach the signal and end checks.
      for (int taken = 1; taken < kMaxBatch; ++taken) {
        std::optional<Item> more = queue_.TryPop();
        if (!more) break;
        Take(std::move(*more));
      }
    } else if (wait_hook_) {
      wait_hook_();
    }
    CheckEnd(NowNs());
  }
}

void LiveSensorSource::Take(Item item) {
  last_sample_ns_ = NowNs();  // only this entity's samples are queued (Enqueue)
  std::visit(
      [this](auto& sample) {
        using Sample = std::decay_t<decltype(sample)>;
        if constexpr (std::is_same_v<Sample, pena_dds::SensorStreamStatus>) {
          TakeStatus(sample);
        } else {
          TakeSample(sample, TopicOf<Sample>());
        }
      },
      item);
}

template <class Sample>
void LiveSensorSource::TakeSample(const Sample& sample, SensorTopic topic) {
  const std::size_t index = Index(topic);
  ++counts_.received[index];
  seq_gaps_.Saw(sample.seq());
  SensorCheck check = FromDds(sample);
  if (!check.record) {
    const std::size_t refused = ++counts_.refused[index];
    if (WorthLogging(refused)) {
      spdlog::warn("{}: {} sample seq {} refused: {} ({} refused on this topic)",
                   options_.entity_id, TopicName(topic), sample.seq(), check.error, refused);
    }
    return;
  }
  if (check.bad_ranges > 0) {
    counts_.bad_ranges += check.bad_ranges;
    spdlog::debug("{}: {} sample seq {}: {} NaN or negative ranges made no-returns",
                  options_.entity_id, TopicName(topic), sample.seq(), check.bad_ranges);
  }
  Offer({topic, sample.seq(), std::move(*check.record)});
}

void LiveSensorSource::Offer(TopicRecord record) {
  const SensorTopic topic = record.topic;
  const double stamp_s = sensors::StampOf(record.record);
  const std::uint64_t seq = record.seq;
  if (merger_.Add(std::move(record))) return;
  const std::size_t late = merger_.counts().late[Index(topic)];
  counts_.late[Index(topic)] = late;
  if (WorthLogging(late)) {
    spdlog::warn("{}: {} record seq {} at stamp {:.6f} s arrived after records up to {:.6f} s "
                 "were released (reorder window {} s); skipped ({} late on this topic)",
                 options_.entity_id, TopicName(topic), seq, stamp_s,
                 merger_.released_stamp_s().value_or(0.0), options_.merge.reorder_window_s,
                 late);
  }
}

void LiveSensorSource::TakeStatus(const pena_dds::SensorStreamStatus& status) {
  if (status.schema_version() != pena_dds::SCHEMA_VERSION) {
    spdlog::warn("{}: {} marker refused: schema_version {}, this reader knows {}",
                 options_.entity_id, topics::kSensorStatus.name, status.schema_version(),
                 pena_dds::SCHEMA_VERSION);
    return;
  }
  if (status.state() == pena_dds::SENSORS_STARTED) {
    if (started_) {
      spdlog::warn("{}: a second start marker (stamp {:.3f} s) ignored", options_.entity_id,
                   status.stamp_s());
      return;
    }
    started_ = true;
    description_.kind = status.kind() == pena_dds::ENTITY_HUMAN ? sensors::EntityKind::kHuman
                                                                : sensors::EntityKind::kRobot;
    description_.mission = status.mission().to_string();
    spdlog::info("{}: sensor stream started (mission '{}', first stamp {:.3f} s{})",
                 options_.entity_id, description_.mission, status.stamp_s(),
                 status.start_pose_known() ? ", known start pose" : "");
    const pena_dds::Pose2& start = status.world_from_body_start();
    if (status.start_pose_known() && std::isfinite(status.stamp_s()) &&
        std::isfinite(start.x_m()) && std::isfinite(start.y_m()) &&
        std::isfinite(start.theta_rad())) {
      // The start pose travels as the ground-truth record a simulated log states before its
      // first scan: the entity takes its start from there exactly as from a file.
      sensors::GroundTruth truth;
      truth.stamp_s = status.stamp_s();
      truth.world_from_body = {start.x_m(), start.y_m(), start.theta_rad()};
      Offer({SensorTopic::kStart, 0, truth});
    }
    return;
  }
  if (status.state() != pena_dds::SENSORS_ENDED) {
    spdlog::warn("{}: {} marker with unknown state {} ignored", options_.entity_id,
                 topics::kSensorStatus.name, static_cast<int>(status.state()));
    return;
  }
  if (!end_marker_) {
    end_marker_ = status;
    end_deadline_ns_ = NowNs() + SecondsToNs(options_.end_grace_s);
  }
}

void LiveSensorSource::CheckEnd(std::int64_t now_ns) {
  if (end_marker_) {
    const std::array<std::uint64_t, 5> sent{end_marker_->scans(), end_marker_->gyro(),
                                            end_marker_->compass(), end_marker_->stride(),
                                            end_marker_->wheel_odometry()};
    bool all = true;
    for (std::size_t i = 0; i < sent.size(); ++i) all = all && counts_.received[i] >= sent[i];
    if (all) return End("end marker");
    if (now_ns >= end_deadline_ns_) {
      for (std::size_t i = 0; i < sent.size(); ++i) {
        if (counts_.received[i] < sent[i]) {
          spdlog::warn("{}: {}: the end marker counts {} samples, {} arrived within {} s",
                       options_.entity_id, TopicName(static_cast<SensorTopic>(i)), sent[i],
                       counts_.received[i], options_.end_grace_s);
        }
      }
      return End("end marker");
    }
  }
  if (options_.idle_timeout_s > 0.0 &&
      now_ns - last_sample_ns_ >= SecondsToNs(options_.idle_timeout_s)) {
    spdlog::warn("{}: no sensor sample for {} s: the live input ends", options_.entity_id,
                 options_.idle_timeout_s);
    End("idle timeout");
  }
}

void LiveSensorSource::End(const std::string& reason) {
  if (ended_) return;
  ended_ = true;
  end_reason_ = reason;
  counts_.gaps = seq_gaps_.Counts();
  LogSummary();
}

void LiveSensorSource::LogSummary() const {
  std::string topics;
  for (std::size_t i = 0; i + 1 < kSensorTopicCount; ++i) {
    if (counts_.received[i] == 0) continue;
    topics += fmt::format("; {} {} received, {} refused, {} late",
                          TopicName(static_cast<SensorTopic>(i)), counts_.received[i],
                          counts_.refused[i], counts_.late[i]);
  }
  spdlog::info("{}: live input ended ({}): {} records to the chain{}; {} NaN or negative ranges made "
               "no-returns; {} samples of other entities ignored",
               options_.entity_id, end_reason_, counts_.released + merger_.held(), topics,
               counts_.bad_ranges, other_entity_.load());
  const SeqGapCounts& gaps = counts_.gaps;
  if (gaps.missed_at_start > 0) {
    spdlog::warn("{}: the first {} sensor samples never arrived (the entity joined the stream "
                 "late); the chain started from the first that did",
                 options_.entity_id, gaps.missed_at_start);
  }
  if (gaps.missed > 0) {
    spdlog::warn("{}: {} sensor samples never arrived after the first (lost on the way, or "
                 "overwritten in a keep-last history); the chain went on from what arrived",
                 options_.entity_id, gaps.missed);
  }
  if (gaps.repeated_or_late > 0) {
    spdlog::warn("{}: {} sensor samples arrived twice or after their gap had been given up "
                 "(a restarted publisher counts from 1 again)",
                 options_.entity_id, gaps.repeated_or_late);
  }
}

}  // namespace pena::services
