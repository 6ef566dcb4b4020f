#pragma once
// Scans a log delivers late: the intel log, during turns on the spot, re-delivers a scan taken
// up to two seconds earlier with the current stamp and odometry (scan 11550 repeats scan 11541
// beam for beam). Matched, such a scan lands where the earlier scan was taken; made a keyframe,
// it anchors the next priors there and the heading error stays (29 deg on intel).

#include <cstddef>
#include <deque>
#include <vector>

#include "pena/sensors/laser_scan.hpp"

namespace pena::odometry::internal {

// Remembers the last few scans' ranges and recognises a repeat of one of them.
class StaleScanDetector {
 public:
  // history_scans = 0 disables the detector. A scan is stale when the median absolute range
  // difference to one of the last history_scans scans other than the previous one is at most
  // repeat_m, while the median difference to the previous scan exceeds changed_m (the scene
  // changed since, so the repeat is not just a robot standing still).
  StaleScanDetector(int history_scans, double repeat_m, double changed_m);

  // Whether `scan` repeats an earlier scan; the scan is remembered either way.
  bool IsStale(const sensors::LaserScan& scan);

 private:
  int history_scans_;
  double repeat_m_;
  double changed_m_;
  std::deque<std::vector<float>> history_;  // newest last; ranges with no-returns as NaN
  std::vector<double> differences_;         // scratch for the median
};

// Median of |a_i - b_i| over the beams valid in both (NaN marks a no-return); NaN when fewer than
// half the beams are valid in both or the sizes differ.
double MedianRangeDifference(const std::vector<float>& a, const std::vector<float>& b,
                             std::vector<double>& scratch);

}  // namespace pena::odometry::internal
