#pragma once
// Timing quality of a log: whether scans arrive in bursts. The intel log stamps scans when they
// were delivered, not when they were taken: 4671 of its 13631 scans are stamped within 20 ms of
// the previous one (a 180-beam laser cannot scan that fast), aces and mit-csail none. A scan's
// stamp then says little about when it was taken, so the odometry paired with it may be another
// scan's, and its pose is less certain than a regularly stamped scan's.

#include <deque>
#include <optional>

namespace pena::odometry::internal {

// Counts scans stamped within burst_gap_s of the previous one over the last window_scans scans
// (0: all scans so far), and calls the timing poor while that fraction exceeds max_fraction.
class BurstTiming {
 public:
  // burst_gap_s <= 0 disables the check (timing is never poor).
  BurstTiming(double burst_gap_s, double max_fraction, int window_scans);

  // Records one scan's stamp (increasing); returns whether the timing is poor after it.
  bool Add(double stamp_s);
  // The fraction of scans in bursts over the window so far.
  double fraction() const;
  // The mean interval between all scans recorded so far (0 before the second): the laser's
  // period where the stamps themselves are delivery times.
  double mean_interval_s() const;

 private:
  double burst_gap_s_;
  double max_fraction_;
  int window_scans_;
  std::optional<double> last_stamp_s_;
  std::optional<double> first_stamp_s_;
  long all_scans_ = 0;
  std::deque<bool> window_;  // newest last; only with window_scans > 0
  long scans_ = 0;
  long bursts_ = 0;
};

}  // namespace pena::odometry::internal
