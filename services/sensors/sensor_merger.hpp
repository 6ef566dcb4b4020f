#pragma once
// Merges the live sensor topics into one stream in stamp order (no DDS here, so it is tested on
// its own). Records of different topics arrive out of order between topics; the merger holds
// each record until one at least reorder_window_s of sensor time newer has arrived, then
// releases the oldest held. A record older than one already released cannot be put back in
// order: Add refuses it and counts it as late.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "pena/sensors/record.hpp"

namespace pena::services {

// Where a record came from. kStart is the start pose the status topic announced (a ground-truth
// record at the stream's first stamp).
enum class SensorTopic { kScan, kGyro, kCompass, kStride, kWheelOdometry, kStart };
inline constexpr std::size_t kSensorTopicCount = 6;

// The topic's DDS name ("pena/sensors/scan", ...).
const char* TopicName(SensorTopic topic);

// One record with the order key its publisher gave it.
struct TopicRecord {
  SensorTopic topic = SensorTopic::kScan;
  std::uint64_t seq = 0;  // the publisher's record number: orders records of equal stamp
  sensors::SensorRecord record;
};

struct SensorMergerOptions {
  // Sensor seconds a record is held for records of other topics that may still arrive older.
  // >= 0 and finite; 0 releases in arrival order (refusing only what goes back in time).
  double reorder_window_s = 0.2;
  // Records held at most; beyond it the oldest is released whatever the window (a publisher whose
  // clock stands still). >= 1.
  std::size_t max_held = 10000;
};

// Per topic: records taken and records refused as too late.
struct MergeCounts {
  std::array<std::size_t, kSensorTopicCount> accepted{};
  std::array<std::size_t, kSensorTopicCount> late{};
};

class SensorMerger {
 public:
  // Throws std::invalid_argument naming reorder_window_s.
  explicit SensorMerger(SensorMergerOptions options);

  // Holds `record`; false (counted late, not held) if it sorts before a released record.
  bool Add(TopicRecord record);
  // The oldest held record once a record reorder_window_s newer arrived, or more than max_held
  // are held; nullopt otherwise.
  std::optional<TopicRecord> PopReady();
  // The oldest held record whatever the window (the stream ended); nullopt when none is held.
  std::optional<TopicRecord> PopOldest();

  std::size_t held() const { return held_.size(); }
  const MergeCounts& counts() const { return counts_; }
  // Stamp of the last released record (nullopt before the first).
  std::optional<double> released_stamp_s() const;

 private:
  struct Key {
    double stamp_s;
    std::uint64_t seq;
    int topic;
    bool operator<(const Key& other) const;
  };
  struct Later {  // min-heap on Key
    bool operator()(const TopicRecord& a, const TopicRecord& b) const;
  };
  static Key KeyOf(const TopicRecord& record);

  SensorMergerOptions options_;
  std::vector<TopicRecord> held_;  // a min-heap on Key (std::push_heap with Later)
  double newest_stamp_s_ = 0.0;
  bool any_ = false;
  std::optional<Key> released_;
  MergeCounts counts_;
};

}  // namespace pena::services
