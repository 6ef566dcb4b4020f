#pragma once
// When the scans win over the motion prior (the prior-consistency gate's confirmation). A match
// outside the gate is either the motion sensor being wrong or the matcher being wrong (an
// aliased optimum along a corridor). A wrong prior is wrong by about the same offset at every
// scan, so the scans agree with each other on where the body is; an aliased match sticks to one
// place while the prior walks on, or jumps between places, so consecutive deviations differ by a
// stride or more (loop170 seed 3 at 177 s: 0.51, 1.24, 1.49 m from the prior, then trusted).

#include "pena/geometry/pose2.hpp"

namespace pena::odometry::internal {

// Counts gated matches in a row; with an agreement tolerance only matches whose deviation from
// the prior agrees with the previous gated match's count on (a disagreeing one starts a new run).
class GateConfirmation {
 public:
  // agree_m = 0: every gated match counts (a plain count, as for wheel odometry).
  GateConfirmation(double agree_m, double agree_rad);

  // A match outside the gate, `deviation` = prior^-1 * match (the prior's body frame). True when
  // it is the `confirm`-th agreeing one in a row: the scans are trusted and the run restarts.
  // agree = false: this match counts whatever its deviation (the prior is known to be unreliable).
  bool Outside(const geometry::Pose2& deviation, int confirm, bool agree = true);
  // A match inside the gate (or a scan that was not matched): the run is over.
  void Inside() { in_row_ = 0; }

  int in_row() const { return in_row_; }

 private:
  bool Agrees(const geometry::Pose2& deviation, bool agree) const;

  double agree_m_;
  double agree_rad_;
  int in_row_ = 0;
  geometry::Pose2 previous_;  // the previous gated match's deviation (valid while in_row_ > 0)
};

}  // namespace pena::odometry::internal
