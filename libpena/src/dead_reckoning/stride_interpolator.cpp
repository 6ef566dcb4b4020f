#include "pena/dead_reckoning/stride_interpolator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::dead_reckoning {
namespace {

void RequirePositive(double value, const char* field) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw std::invalid_argument(std::string("dead_reckoning.stride_interpolation.") + field +
                                " must be a finite value > 0, got " + std::to_string(value));
  }
}

}  // namespace

StrideInterpolator::StrideInterpolator(const StrideInterpolationOptions& options)
    : options_(options) {
  Validate(options);
}

void StrideInterpolator::Validate(const StrideInterpolationOptions& options) {
  RequirePositive(options.max_hold_s, "max_hold_s");
  RequirePositive(options.max_stride_period_s, "max_stride_period_s");
  RequirePositive(options.default_stride_period_s, "default_stride_period_s");
  RequirePositive(options.max_stride_m, "max_stride_m");
  if (options.max_held_records < 1) {
    throw std::invalid_argument(
        "dead_reckoning.stride_interpolation.max_held_records must be >= 1");
  }
}

void StrideInterpolator::Push(sensors::SensorRecord record) {
  const double stamp_s = sensors::StampOf(record);
  // The latest stamp, not the largest: one record stamped far ahead (a glitch the dead
  // reckoning ignores) must not make every later record stale.
  if (std::isfinite(stamp_s)) latest_s_ = stamp_s;
  if (const auto* stride = std::get_if<sensors::StrideSample>(&record)) {
    const bool usable = std::isfinite(stride->stamp_s) && std::isfinite(stride->length_m) &&
                        stride->length_m >= 0.0 && stride->length_m <= options_.max_stride_m &&
                        (!last_stride_s_ || stride->stamp_s >= *last_stride_s_);
    if (usable) {
      SpreadStride(*stride);
      return;
    }
    // Passed on whole, after what it follows, for the dead reckoning to reject and count. A
    // step was still taken then: an in-order stamp ends the stride the next report spreads.
    const bool in_order = std::isfinite(stride->stamp_s) &&
                          (!last_stride_s_ || stride->stamp_s >= *last_stride_s_);
    const double stride_stamp_s = stride->stamp_s;
    ReleaseHeld();
    ready_.push_back(std::move(record));
    if (in_order) last_stride_s_ = stride_stamp_s;
    return;
  }
  held_.push_back(std::move(record));
  ReleaseStale();
}

std::optional<sensors::SensorRecord> StrideInterpolator::Pop() {
  if (ready_.empty()) return std::nullopt;
  sensors::SensorRecord record = std::move(ready_.front());
  ready_.pop_front();
  return record;
}

void StrideInterpolator::Finish() { ReleaseHeld(); }

void StrideInterpolator::SpreadStride(const sensors::StrideSample& stride) {
  const double end_s = stride.stamp_s;
  const bool walking = last_stride_s_ && end_s - *last_stride_s_ <= options_.max_stride_period_s;
  // A stride after standing (or the first) began one period before its report, not at the
  // previous report; what was already released without a report cannot be moved any more.
  double start_s = walking ? *last_stride_s_
                           : end_s - last_period_s_.value_or(options_.default_stride_period_s);
  if (released_until_s_) start_s = std::max(start_s, *released_until_s_);
  if (last_stride_s_) start_s = std::max(start_s, *last_stride_s_);  // no piece before a report
  const double span_s = end_s - start_s;
  double cut_s = start_s;
  double spread_m = 0.0;
  bool spread = false;
  bool rest_out = false;
  // The rest at the report itself, before any record held with its stamp (a scan taken as the
  // stride ended sees all of it): the pieces add up to the reported length.
  const auto put_rest = [&] {
    ready_.push_back(sensors::StrideSample{end_s, std::max(stride.length_m - spread_m, 0.0)});
    rest_out = true;
  };
  // Records stamped after the report (within the hold: a stamp far ahead is a glitch) belong to
  // the next stride: they stay held, with everything after them.
  std::deque<sensors::SensorRecord> later;
  for (sensors::SensorRecord& record : held_) {
    const double record_s = sensors::StampOf(record);
    if (!later.empty() || (record_s > end_s && record_s <= end_s + options_.max_hold_s)) {
      later.push_back(std::move(record));
      continue;
    }
    if (!rest_out && sensors::StampOf(record) >= end_s) put_rest();
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (!rest_out && span_s > 0.0 && scan && scan->stamp_s > cut_s) {
      // The part of the stride walked since the previous cut, the pace taken as steady.
      const double piece_m = stride.length_m * (scan->stamp_s - cut_s) / span_s;
      ready_.push_back(sensors::StrideSample{scan->stamp_s, piece_m});
      spread_m += piece_m;
      cut_s = scan->stamp_s;
      spread = true;
      ++counts_.pieces;
    }
    ready_.push_back(std::move(record));
  }
  held_.swap(later);
  if (!rest_out) put_rest();
  if (spread) ++counts_.strides_spread;
  if (walking) last_period_s_ = end_s - *last_stride_s_;
  last_stride_s_ = end_s;
}

void StrideInterpolator::NoteReleased(double stamp_s) {
  // A stamp beyond the hold ahead of the stream is a glitch, not how far the stream got.
  if (!std::isfinite(stamp_s) || (latest_s_ && stamp_s > *latest_s_ + options_.max_hold_s)) return;
  released_until_s_ = released_until_s_ ? std::max(*released_until_s_, stamp_s) : stamp_s;
}

void StrideInterpolator::ReleaseHeld() {
  for (sensors::SensorRecord& record : held_) {
    const double stamp_s = sensors::StampOf(record);
    NoteReleased(stamp_s);
    ready_.push_back(std::move(record));
    ++counts_.released_unspread;
  }
  held_.clear();
}

void StrideInterpolator::ReleaseStale() {
  while (!held_.empty()) {
    const double stamp_s = sensors::StampOf(held_.front());
    // Stale: waited the hold, or stamped beyond it ahead of the stream (a glitch: it must not
    // hold everything behind it).
    const bool stale = !std::isfinite(stamp_s) || held_.size() > options_.max_held_records ||
                       (latest_s_ && (stamp_s < *latest_s_ - options_.max_hold_s ||
                                      stamp_s > *latest_s_ + options_.max_hold_s));
    if (!stale) return;
    NoteReleased(stamp_s);
    ready_.push_back(std::move(held_.front()));
    held_.pop_front();
    ++counts_.released_unspread;
  }
}

std::vector<sensors::SensorRecord> SpreadStrides(std::vector<sensors::SensorRecord> records,
                                                 const StrideInterpolationOptions& options) {
  if (!options.enabled) return records;
  StrideInterpolator spread(options);
  std::vector<sensors::SensorRecord> out;
  out.reserve(records.size() + records.size() / 8);
  for (sensors::SensorRecord& record : records) {
    spread.Push(std::move(record));
    while (auto ready = spread.Pop()) out.push_back(std::move(*ready));
  }
  spread.Finish();
  while (auto ready = spread.Pop()) out.push_back(std::move(*ready));
  return out;
}

}  // namespace pena::dead_reckoning
