#pragma once
// When the scans win over the motion prior (the prior-consistency gate's confirmation): after
// `confirm` matches in a row outside the gate the motion sensor, not the matcher, is taken to be
// what is wrong.

namespace pena::odometry::internal {

// Counts gated matches in a row.
class GateConfirmation {
 public:
  // A match outside the gate. True when it is the `confirm`-th in a row: the scans are trusted
  // and the run restarts.
  bool Outside(int confirm) {
    if (++in_row_ < confirm) return false;
    in_row_ = 0;
    return true;
  }
  // A match inside the gate (or a scan that was not matched): the run is over.
  void Inside() { in_row_ = 0; }

  int in_row() const { return in_row_; }

 private:
  int in_row_ = 0;
};

}  // namespace pena::odometry::internal
