#include "sensor_merger.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace pena::services {

const char* TopicName(SensorTopic topic) {
  switch (topic) {
    case SensorTopic::kScan: return "pena/sensors/scan";
    case SensorTopic::kGyro: return "pena/sensors/gyro";
    case SensorTopic::kCompass: return "pena/sensors/compass";
    case SensorTopic::kStride: return "pena/sensors/stride";
    case SensorTopic::kWheelOdometry: return "pena/sensors/wheel_odometry";
    case SensorTopic::kStart: return "pena/sensors/status";
  }
  return "?";
}

SensorMerger::SensorMerger(SensorMergerOptions options) : options_(options) {
  if (!std::isfinite(options_.reorder_window_s) || options_.reorder_window_s < 0.0) {
    throw std::invalid_argument("reorder_window_s must be a finite number >= 0 s, got " +
                                std::to_string(options_.reorder_window_s));
  }
  if (options_.max_held < 1) throw std::invalid_argument("max_held must be >= 1 record, got 0");
}

bool SensorMerger::Key::operator<(const Key& other) const {
  return std::tie(stamp_s, seq, topic) < std::tie(other.stamp_s, other.seq, other.topic);
}

bool SensorMerger::Later::operator()(const TopicRecord& a, const TopicRecord& b) const {
  return KeyOf(b) < KeyOf(a);
}

SensorMerger::Key SensorMerger::KeyOf(const TopicRecord& record) {
  return {sensors::StampOf(record.record), record.seq, static_cast<int>(record.topic)};
}

bool SensorMerger::Add(TopicRecord record) {
  const auto topic = static_cast<std::size_t>(record.topic);
  const Key key = KeyOf(record);
  // Releasing it now would put it behind a record that sorts after it.
  if (released_ && key < *released_) {
    ++counts_.late[topic];
    return false;
  }
  ++counts_.accepted[topic];
  newest_stamp_s_ = any_ ? std::max(newest_stamp_s_, key.stamp_s) : key.stamp_s;
  any_ = true;
  held_.push_back(std::move(record));
  std::push_heap(held_.begin(), held_.end(), Later{});
  return true;
}

std::optional<TopicRecord> SensorMerger::PopReady() {
  if (held_.empty()) return std::nullopt;
  if (held_.size() <= options_.max_held &&
      newest_stamp_s_ - sensors::StampOf(held_.front().record) < options_.reorder_window_s) {
    return std::nullopt;
  }
  return PopOldest();
}

std::optional<TopicRecord> SensorMerger::PopOldest() {
  if (held_.empty()) return std::nullopt;
  std::pop_heap(held_.begin(), held_.end(), Later{});
  TopicRecord out = std::move(held_.back());
  held_.pop_back();
  released_ = KeyOf(out);
  return out;
}

std::optional<double> SensorMerger::released_stamp_s() const {
  if (!released_) return std::nullopt;
  return released_->stamp_s;
}

}  // namespace pena::services
