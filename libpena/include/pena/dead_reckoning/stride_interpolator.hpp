#pragma once
// Spreads each stride report over the scans taken during its stride, at the cost of a short delay.
//
// The SiLMU reports a stride when it ends, so a dead reckoning that moves only at reports is
// behind the walker by anything from nothing to a whole stride at every scan: a saw tooth of up
// to 0.55 m at 1 m/s. In a corridor the scan matcher cannot see the along-track position, so the
// odometry inherits that saw tooth (docs/dead-reckoning.md). Extrapolating the last stride's pace
// guesses the stride in progress and must take the guess back at the next report; waiting for
// the report does not guess: the records of a stride are held until the report that ends it, and
// the stride is then cut at every scan inside it, in proportion to time (the walker's pace is
// steady within one step). The dead reckoning sees the same stream with the stride's pieces in
// front of those scans, so its position at every report is exactly as before.

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "pena/sensors/record.hpp"

namespace pena::dead_reckoning {

// Validated by StrideInterpolator's constructor.
struct StrideInterpolationOptions {
  bool enabled = true;
  // A record waits at most this long (behind the latest stamp pushed) for its stride's report; a
  // walker who stopped sends none, and the records go on as they are. This is the added latency.
  double max_hold_s = 1.0;
  // A report more than this after the previous one ends a stride begun after standing: it is
  // taken to span the previous stride's period (default_stride_period_s for the first).
  double max_stride_period_s = 1.5;
  double default_stride_period_s = 0.55;
  // Reports outside [0, max_stride_m] or not finite are passed on whole, for the dead reckoning
  // to reject (HumanDeadReckoningOptions::max_stride_m): cut up, a 40 m fault would be accepted.
  double max_stride_m = 2.0;
  // Bound on the records held (hostile streams whose stamps do not advance).
  std::size_t max_held_records = 20000;
};

// What the interpolator did, for logs and reports.
struct StrideInterpolationCounts {
  std::size_t strides_spread = 0;   // reports cut at one scan or more
  std::size_t pieces = 0;           // pieces put in front of scans
  std::size_t released_unspread = 0;  // records released by max_hold_s or max_held_records
};

// Push records in log order; Pop them (with the pieces) in the order to process them. Records
// are never dropped, changed or reordered among themselves: only held, and strides cut.
class StrideInterpolator {
 public:
  // Throws std::invalid_argument naming the field if an option is out of range.
  explicit StrideInterpolator(const StrideInterpolationOptions& options);
  static void Validate(const StrideInterpolationOptions& options);

  void Push(sensors::SensorRecord record);
  // The next record ready to process, or nullopt while the rest waits for a report.
  std::optional<sensors::SensorRecord> Pop();
  // End of the stream: everything held is ready.
  void Finish();

  const StrideInterpolationCounts& counts() const { return counts_; }

 private:
  void SpreadStride(const sensors::StrideSample& stride);
  void ReleaseHeld();
  void ReleaseStale();
  void NoteReleased(double stamp_s);

  StrideInterpolationOptions options_;
  std::deque<sensors::SensorRecord> held_;   // waiting for a report
  std::deque<sensors::SensorRecord> ready_;  // to Pop
  std::optional<double> last_stride_s_;      // the last report passed on
  std::optional<double> last_period_s_;      // its stride's span
  std::optional<double> released_until_s_;   // the latest stamp released without a report
  std::optional<double> latest_s_;           // the latest finite stamp pushed
  StrideInterpolationCounts counts_;
};

// A whole recorded stream through a StrideInterpolator (as is when options.enabled is false).
std::vector<sensors::SensorRecord> SpreadStrides(std::vector<sensors::SensorRecord> records,
                                                 const StrideInterpolationOptions& options);

}  // namespace pena::dead_reckoning
