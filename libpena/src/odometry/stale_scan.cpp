#include "stale_scan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pena::odometry::internal {

StaleScanDetector::StaleScanDetector(int history_scans, double repeat_m, double changed_m)
    : history_scans_(history_scans), repeat_m_(repeat_m), changed_m_(changed_m) {}

double MedianRangeDifference(const std::vector<float>& a, const std::vector<float>& b,
                             std::vector<double>& scratch) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (a.size() != b.size() || a.empty()) return kNaN;
  scratch.clear();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isnan(a[i]) && !std::isnan(b[i])) scratch.push_back(std::abs(double{a[i]} - b[i]));
  }
  if (2 * scratch.size() < a.size()) return kNaN;
  const auto middle = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
  std::nth_element(scratch.begin(), middle, scratch.end());
  return *middle;
}

bool StaleScanDetector::IsStale(const sensors::LaserScan& scan) {
  if (history_scans_ <= 0) return false;
  std::vector<float> ranges(scan.ranges_m.size());
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    ranges[i] = scan.IsReturn(i) ? scan.ranges_m[i] : std::numeric_limits<float>::quiet_NaN();
  }
  bool stale = false;
  if (history_.size() >= 2) {
    const double to_previous = MedianRangeDifference(ranges, history_.back(), differences_);
    if (to_previous > changed_m_) {
      for (std::size_t k = 0; k + 1 < history_.size() && !stale; ++k) {
        stale = MedianRangeDifference(ranges, history_[k], differences_) <= repeat_m_;
      }
    }
  }
  history_.push_back(std::move(ranges));
  while (static_cast<int>(history_.size()) > history_scans_) history_.pop_front();
  return stale;
}

}  // namespace pena::odometry::internal
