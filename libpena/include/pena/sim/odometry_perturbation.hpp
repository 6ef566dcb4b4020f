#pragma once
// A documented noise model for odometry, applied to a log whose odometry is good (a log with
// SLAM-corrected poses) or to any log, so that the chain can be scored on how it copes with bad
// odometry on real scans: a scale error of distance and of turns, a heading random walk with the
// distance travelled, and sudden heading slips (a wheel spinning on a threshold, a bump).

#include <cstdint>

#include "pena/geometry/pose2.hpp"
#include "pena/sim/random.hpp"

namespace pena::sim {

// The noise model; every draw comes from one seeded stream (same seed, same log: same output).
// Validated by OdometryPerturber's constructor (messages name the field and its unit).
struct OdometryNoiseModel {
  double distance_scale_sd = 0.02;  // distance scale error (1 + N(0, sd)), drawn once per run
  double turn_scale_sd = 0.02;      // rotation scale error (1 + N(0, sd)), drawn once per run
  // Heading random walk: each increment adds N(0, sd^2 * distance) to the heading (rad/sqrt(m)).
  double heading_walk_rad_per_sqrt_m = 0.008726646259971648;  // 0.5 deg/sqrt(m)
  // Sudden heading slips: a Poisson process in distance travelled; each slip turns the odometry's
  // heading at once by a magnitude uniform in [slip_min_rad, slip_max_rad] with a random sign.
  double slips_per_m = 0.01;                     // one per 100 m on average
  double slip_min_rad = 0.08726646259971647;     // 5 deg
  double slip_max_rad = 0.5235987755982988;      // 30 deg
};

// Turns a stream of odometry poses (one per sample, in time order) into perturbed ones. The
// first pose is kept; every later one is the previous perturbed pose composed with the perturbed
// increment between the two original poses.
class OdometryPerturber {
 public:
  // Throws std::invalid_argument naming the field if the model is unusable.
  OdometryPerturber(const OdometryNoiseModel& model, std::uint64_t seed);

  // The perturbed pose for the next original odometry pose.
  geometry::Pose2 Perturb(const geometry::Pose2& odom_pose);

  int slips() const { return slips_; }                    // slips applied so far
  double distance_scale() const { return distance_scale_; }
  double turn_scale() const { return turn_scale_; }

 private:
  OdometryNoiseModel model_;
  Random random_;
  double distance_scale_;
  double turn_scale_;
  bool started_ = false;
  geometry::Pose2 previous_original_;
  geometry::Pose2 previous_perturbed_;
  int slips_ = 0;
};

}  // namespace pena::sim
