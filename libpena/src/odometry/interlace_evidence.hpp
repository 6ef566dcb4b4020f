#pragma once
// Which interlace a laser has, decided from its own scans (docs/odometry.md "Sensor timing"). A
// laser that interleaves sweeps (SICK LMS at 0.5 or 0.25 deg) takes neighbouring beams a mirror
// turn apart; while the platform turns, deskewing by the right interlace puts each return back on
// its surface, while the wrong one shifts alternate returns sideways by range x turn: a zigzag
// along oblique walls. The evidence is how far each return lies from the chord of its two beam
// neighbours, under each hypothesis, over the turning scans.

#include <optional>

#include "pena/sensors/laser_scan.hpp"

namespace pena::odometry::internal {

// Median distance (m) of the returns of `scan`, deskewed at `rotation_rate_rad_s` with `geometry`,
// from the chord through their two beam neighbours, over beams whose neighbours are returns too;
// nullopt with fewer than 10 such beams.
std::optional<double> ContourRoughness(const sensors::LaserScan& scan,
                                       const sensors::LaserGeometry& geometry,
                                       double rotation_rate_rad_s, double min_range_m);

// A sequential test between "one sweep" and the configured interlace (when that is 2 or more):
// each turning scan adds log(roughness one sweep / roughness configured); once the sum leaves
// +-log(1 / kErrorRate) the better hypothesis is kept for the rest of the run. One scan counts as
// one observation although it has hundreds of beams, so the test is conservative.
class InterlaceEvidence {
 public:
  static constexpr double kErrorRate = 0.01;

  // Adds a scan's evidence (nothing once decided, without interlace or without a turn).
  void Add(const sensors::LaserScan& scan, double rotation_rate_rad_s, double min_range_m);
  // The interlace to deskew `configured` scans with: the configured one until decided.
  int Interlace(int configured) const;
  // 1 or the configured interlace once decided; nullopt before.
  std::optional<int> decided() const { return decided_; }

 private:
  double log_ratio_ = 0.0;  // sum of log(roughness one sweep / roughness configured)
  std::optional<int> decided_;
};

}  // namespace pena::odometry::internal
