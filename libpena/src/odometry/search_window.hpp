#pragma once
// The adaptive search window: the paper's window after good matches, grown after a failed match
// (the paper: "the search area is increased for the next round") up to the no-gyro window.

#include "pena/odometry/laser_odometry.hpp"

namespace pena::odometry::internal {

// Scales the base window by a factor, per dimension capped at the wide window.
class WindowScale {
 public:
  explicit WindowScale(const LaserOdometryOptions& options);

  scan_matching::SearchWindow Current() const;
  bool IsBase() const { return factor_ <= 1.0; }
  bool IsWide() const { return factor_ > 1.0; }
  // Multiplies the factor by the growth; false when every dimension is already at its cap.
  bool Grow();
  // Divides the factor by the growth, down to the base window.
  void Shrink();
  void SetWide();

 private:
  double MaxFactor() const;

  scan_matching::SearchWindow base_;
  scan_matching::SearchWindow wide_;
  double growth_;
  double factor_ = 1.0;
};

}  // namespace pena::odometry::internal
