#pragma once
// Online calibration of the stride sensor's scale from position fixes (scan matching): where the
// position is fixed in every direction, the distance really walked against the raw stride walk
// gives the scale, which then applies in corridors where the strides alone give the position.

#include <Eigen/Core>
#include <optional>

namespace pena::dead_reckoning {

// Options of the calibration. Validated by StrideCalibration's constructor.
struct StrideCalibrationOptions {
  bool enabled = false;  // docs/dead-reckoning.md
  double interval_m = 2.0;        // raw stride walk between the two fixes of one sample
  double prior_weight_m2 = 8.0;   // weight of the prior scale 1, as sum of |walk|^2 (two 2 m samples)
  double max_correction = 0.2;    // the scale stays within [1 - max, 1 + max]
};

// Least-squares scale s minimising sum |fix displacement - s * raw walk|^2 over the samples, with
// a prior s = 1 of weight prior_weight_m2.
class StrideCalibration {
 public:
  // Throws std::invalid_argument naming the field if an option is out of range.
  explicit StrideCalibration(const StrideCalibrationOptions& options);

  // A position fix: raw_walk_m is the unscaled stride walk (sum of strides along the heading) at
  // the fix, world_position_m the fixed position. continuous = false when something between the
  // previous fix and this one was not constrained (a corridor, a failed match): the sample is
  // restarted here.
  void AddFix(const Eigen::Vector2d& raw_walk_m, const Eigen::Vector2d& world_position_m,
              bool continuous);

  double scale() const { return scale_; }
  int samples() const { return samples_; }

 private:
  struct Anchor {
    Eigen::Vector2d raw_walk_m;
    Eigen::Vector2d world_position_m;
  };

  StrideCalibrationOptions options_;
  std::optional<Anchor> anchor_;
  double sum_fix_dot_walk_m2_ = 0.0;
  double sum_walk_dot_walk_m2_ = 0.0;
  double scale_ = 1.0;
  int samples_ = 0;
};

}  // namespace pena::dead_reckoning
