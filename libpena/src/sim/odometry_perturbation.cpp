#include "pena/sim/odometry_perturbation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"

namespace pena::sim {
namespace {

void CheckModel(const OdometryNoiseModel& m) {
  const auto non_negative = [](double value, const char* field, const char* unit) {
    RequireOption(value >= 0.0 && std::isfinite(value), "odometry_noise", field,
                  std::string(">= 0 ") + unit + ", finite", value);
  };
  non_negative(m.distance_scale_sd, "distance_scale_sd", "(fraction)");
  non_negative(m.turn_scale_sd, "turn_scale_sd", "(fraction)");
  non_negative(m.heading_walk_rad_per_sqrt_m, "heading_walk_rad_per_sqrt_m", "rad/sqrt(m)");
  non_negative(m.slips_per_m, "slips_per_m", "1/m");
  non_negative(m.slip_min_rad, "slip_min_rad", "rad");
  RequireOption(m.slip_max_rad >= m.slip_min_rad && m.slip_max_rad <= 3.141592653589793,
                "odometry_noise", "slip_max_rad", ">= slip_min_rad and <= pi rad",
                m.slip_max_rad);
}

}  // namespace

OdometryPerturber::OdometryPerturber(const OdometryNoiseModel& model, std::uint64_t seed)
    : model_((CheckModel(model), model)), random_(seed) {
  distance_scale_ = 1.0 + random_.Normal(0.0, model_.distance_scale_sd);
  turn_scale_ = 1.0 + random_.Normal(0.0, model_.turn_scale_sd);
}

geometry::Pose2 OdometryPerturber::Perturb(const geometry::Pose2& odom_pose) {
  if (!started_) {
    started_ = true;
    previous_original_ = previous_perturbed_ = odom_pose;
    return odom_pose;
  }
  const geometry::Pose2 increment = geometry::Between(previous_original_, odom_pose);
  previous_original_ = odom_pose;
  const double distance_m = std::hypot(increment.x_m, increment.y_m);
  geometry::Pose2 noisy{increment.x_m * distance_scale_, increment.y_m * distance_scale_,
                        increment.theta_rad * turn_scale_};
  noisy.theta_rad += random_.Normal(0.0, model_.heading_walk_rad_per_sqrt_m * std::sqrt(distance_m));
  // A Poisson process in distance: at most one slip per increment (increments are centimetres).
  if (random_.Bernoulli(1.0 - std::exp(-model_.slips_per_m * distance_m))) {
    const double magnitude_rad = random_.Uniform(model_.slip_min_rad, model_.slip_max_rad);
    noisy.theta_rad += random_.Bernoulli(0.5) ? magnitude_rad : -magnitude_rad;
    ++slips_;
  }
  previous_perturbed_ = geometry::Compose(previous_perturbed_, noisy);
  previous_perturbed_.theta_rad = geometry::NormalizeAngle(previous_perturbed_.theta_rad);
  return previous_perturbed_;
}

}  // namespace pena::sim
