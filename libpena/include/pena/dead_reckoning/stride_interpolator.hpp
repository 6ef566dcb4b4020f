#pragma once
// Spreads each stride report over the scans taken during its stride, at the cost of a short delay.
//
// The SiLMU reports a stride when it ends, so a dead reckoning that moves only at reports lags the
// walker by up to a stride at every scan, which the odometry inherits in corridors. The records of
// a stride are held until the report that ends it, and the stride is cut at every scan inside it
// in proportion to time; the position at every report is unchanged (docs/dead-reckoning.md).

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "pena/sensors/record.hpp"

namespace pena::dead_reckoning {

// Validated by StrideInterpolator's constructor.
struct StrideInterpolationOptions {
  bool enabled = true;
  double max_hold_s = 1.0;  // longest wait for a stride's report (the added latency), s
  // A report this long after the previous one ends a stride begun after standing (it spans the
  // previous stride's period, or default_stride_period_s for the first).
  double max_stride_period_s = 1.5;
  double default_stride_period_s = 0.55;
  double max_stride_m = 2.0;  // longer or non-finite reports pass whole, for the dead reckoning to reject
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
