#include "burst_timing.hpp"

namespace pena::odometry::internal {

BurstTiming::BurstTiming(double burst_gap_s, double max_fraction, int window_scans)
    : burst_gap_s_(burst_gap_s), max_fraction_(max_fraction), window_scans_(window_scans) {}

bool BurstTiming::Add(double stamp_s) {
  if (!first_stamp_s_) first_stamp_s_ = stamp_s;
  ++all_scans_;
  if (burst_gap_s_ <= 0.0) {
    last_stamp_s_ = stamp_s;
    return false;
  }
  const bool in_burst = last_stamp_s_ && stamp_s - *last_stamp_s_ < burst_gap_s_;
  last_stamp_s_ = stamp_s;
  ++scans_;
  bursts_ += in_burst ? 1 : 0;
  if (window_scans_ > 0) {
    window_.push_back(in_burst);
    if (static_cast<int>(window_.size()) > window_scans_) {
      scans_ -= 1;
      bursts_ -= window_.front() ? 1 : 0;
      window_.pop_front();
    }
  }
  return fraction() > max_fraction_;
}

double BurstTiming::fraction() const {
  return scans_ > 0 ? static_cast<double>(bursts_) / static_cast<double>(scans_) : 0.0;
}

double BurstTiming::mean_interval_s() const {
  if (all_scans_ < 2) return 0.0;
  return (*last_stamp_s_ - *first_stamp_s_) / static_cast<double>(all_scans_ - 1);
}

}  // namespace pena::odometry::internal
