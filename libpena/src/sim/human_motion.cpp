#include "pena/sim/human_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pena::sim {
namespace {

using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("human_motion." + what);
}

Vector2d Direction(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

// Moves `value` towards `target` by at most `max_change`.
double Approach(double value, double target, double max_change) {
  return value + std::clamp(target - value, -max_change, max_change);
}

// Discrete Ornstein-Uhlenbeck step: stationary sd `sd`, correlation time `tau_s`.
double OuStep(double value, double sd, double tau_s, double dt_s, Random& random) {
  return value - value * dt_s / tau_s + sd * std::sqrt(2.0 * dt_s / tau_s) * random.Normal();
}

enum class Mode { kWalk, kPause, kStop, kDodge, kFinish };

// A bend of the torso: ramps to peak_rad, holds, ramps back (raised-cosine ramps).
struct Bend {
  double start_s = 0.0;
  double peak_rad = 0.0;
  double hold_s = 0.0;
  bool active = false;
};

// The walking state machine; one instance per Generate call.
class Walker {
 public:
  Walker(const HumanMotionOptions& options, const EntitySpec& spec,
         const std::vector<geometry::Segment2>& walls, Random& random)
      : o_(options),
        spec_(spec),
        walls_(walls),
        random_(random),
        route_(UnrollRoute(spec)),
        dt_s_(1.0 / options.rate_hz),
        position_(spec.start.x_m, spec.start.y_m),
        heading_rad_(spec.start.theta_rad) {}

  TrueMotion Run();

 private:
  void Tick();
  void Walk();
  void Idle();
  Vector2d Carrot() const;
  void MaybeStartEvent(double heading_error_rad, double distance_m);
  bool TryDodge(double direction_rad, double distance_m);
  void AdvanceGait(double moved_m);
  double BendAngle();
  void Record(std::size_t index, const Vector2d& previous_position, double previous_yaw_rad);
  double BodyYaw() const {
    return heading_rad_ + sway_scale_ * o_.yaw_sway_rad * std::sin(kPi * phase_);
  }

  const HumanMotionOptions& o_;
  const EntitySpec& spec_;
  const std::vector<geometry::Segment2>& walls_;
  Random& random_;
  std::vector<Waypoint> route_;
  double dt_s_;
  TrueMotion motion_;

  double t_s_ = 0.0;
  std::size_t target_ = 0;
  Mode mode_ = Mode::kWalk;
  double mode_end_s_ = 0.0;
  Vector2d position_;
  double heading_rad_;  // where the walker faces, without the gait sway
  double turn_rate_rad_s_ = 0.0;
  double speed_m_s_ = 0.0;  // forward walking speed
  double speed_factor_offset_ = 0.0;
  Vector2d dodge_direction_ = Vector2d::Zero();
  double dodge_start_s_ = 0.0;
  double dodge_duration_s_ = 0.0;
  double dodge_peak_m_s_ = 0.0;
  double phase_ = 0.0;       // steps taken, fractional
  double sway_scale_ = 0.0;  // gait intensity of the current step
  double pitch_drift_rad_ = 0.0;
  double roll_drift_rad_ = 0.0;
  Bend bend_;
};

TrueMotion Walker::Run() {
  motion_.rate_hz = o_.rate_hz;
  double route_length_m = 0.0;
  double pauses_s = 0.0;
  Vector2d from = position_;
  for (const Waypoint& waypoint : route_) {
    route_length_m += (waypoint.position_m - from).norm();
    pauses_s += waypoint.pause_s;
    from = waypoint.position_m;
  }
  // Generous: a walker who needs ten times the cruise time is stuck, which is a bug, not data.
  const double time_limit_s =
      10.0 * route_length_m / std::max(spec_.cruise_speed_m_s, 0.1) + pauses_s + 120.0;
  if (route_.empty()) {
    mode_ = Mode::kFinish;
    mode_end_s_ = o_.finish_stand_s;
  }
  Record(0, position_, BodyYaw());
  for (std::size_t index = 1;; ++index) {
    t_s_ = static_cast<double>(index) * dt_s_;
    if (mode_ == Mode::kFinish && t_s_ > mode_end_s_) break;
    if (t_s_ > time_limit_s) {
      throw std::runtime_error(
          "human_motion: entity " + spec_.id + " did not reach waypoint " +
          std::to_string(target_ % std::max<std::size_t>(spec_.route.size(), 1)));
    }
    const Vector2d previous_position = position_;
    const double previous_yaw = BodyYaw();
    Tick();
    Record(index, previous_position, previous_yaw);
  }
  return std::move(motion_);
}

void Walker::Tick() {
  speed_factor_offset_ =
      OuStep(speed_factor_offset_, o_.speed_variation, o_.speed_change_time_s, dt_s_, random_);
  if (mode_ == Mode::kWalk) {
    Walk();
  } else {
    Idle();
  }
  Vector2d velocity = speed_m_s_ * Direction(heading_rad_);
  if (mode_ == Mode::kDodge) {
    // Half-sine speed profile: smooth start and stop, mean speed = dodge_speed.
    const double tau = (t_s_ - dodge_start_s_) / dodge_duration_s_;
    velocity += dodge_peak_m_s_ * std::sin(kPi * std::clamp(tau, 0.0, 1.0)) * dodge_direction_;
  }
  const Vector2d step = velocity * dt_s_;
  position_ += step;
  heading_rad_ = geometry::NormalizeAngle(heading_rad_ + turn_rate_rad_s_ * dt_s_);
  AdvanceGait(step.norm());
  pitch_drift_rad_ =
      OuStep(pitch_drift_rad_, o_.tilt_drift_sd_rad, o_.tilt_drift_time_s, dt_s_, random_);
  roll_drift_rad_ =
      OuStep(roll_drift_rad_, o_.tilt_drift_sd_rad, o_.tilt_drift_time_s, dt_s_, random_);
}

void Walker::Walk() {
  const Waypoint& waypoint = route_[target_];
  const Vector2d to_target = waypoint.position_m - position_;
  const double distance_m = to_target.norm();
  if (distance_m < o_.waypoint_tolerance_m) {
    ++target_;
    if (target_ == route_.size()) {
      mode_ = Mode::kFinish;
      mode_end_s_ = t_s_ + waypoint.pause_s + o_.finish_stand_s;
    } else if (waypoint.pause_s > 0.0) {
      mode_ = Mode::kPause;
      mode_end_s_ = t_s_ + waypoint.pause_s;
    }
    Idle();
    return;
  }
  const Vector2d aim = Carrot();
  const double error_rad = geometry::NormalizeAngle(
      std::atan2(aim.y() - position_.y(), aim.x() - position_.x()) - heading_rad_);
  const double wanted_rate =
      std::clamp(o_.turn_gain_per_s * error_rad, -o_.max_turn_rate_rad_s, o_.max_turn_rate_rad_s);
  turn_rate_rad_s_ = Approach(turn_rate_rad_s_, wanted_rate, o_.max_turn_accel_rad_s2 * dt_s_);
  // People slow down to turn: at 90 deg off course they turn on the spot.
  const double alignment = std::max(0.0, std::cos(error_rad));
  const double factor = std::clamp(1.0 + speed_factor_offset_, 0.6, 1.4);
  const double wanted_speed = spec_.cruise_speed_m_s * factor * alignment * alignment;
  const double limit = (wanted_speed > speed_m_s_ ? o_.acceleration_m_s2 : o_.deceleration_m_s2);
  speed_m_s_ = Approach(speed_m_s_, wanted_speed, limit * dt_s_);
  MaybeStartEvent(error_rad, distance_m);
}

Vector2d Walker::Carrot() const {
  // Pure pursuit of a point lookahead_m ahead on the current leg: after a side step the walker
  // rejoins the leg instead of cutting diagonally towards the waypoint (and through door jambs).
  const Vector2d from =
      target_ == 0 ? Vector2d(spec_.start.x_m, spec_.start.y_m) : route_[target_ - 1].position_m;
  const Vector2d to = route_[target_].position_m;
  const double length_m = (to - from).norm();
  if (length_m < 1e-9 || (to - position_).norm() < o_.lookahead_m) return to;
  const Vector2d along = (to - from) / length_m;
  const double s = std::clamp((position_ - from).dot(along), 0.0, length_m);
  return from + std::min(s + o_.lookahead_m, length_m) * along;
}

void Walker::Idle() {
  speed_m_s_ = Approach(speed_m_s_, 0.0, o_.deceleration_m_s2 * dt_s_);
  turn_rate_rad_s_ = Approach(turn_rate_rad_s_, 0.0, o_.max_turn_accel_rad_s2 * dt_s_);
  if (mode_ != Mode::kFinish && mode_ != Mode::kWalk && t_s_ >= mode_end_s_) mode_ = Mode::kWalk;
}

void Walker::MaybeStartEvent(double heading_error_rad, double distance_m) {
  // Events only on straight stretches, away from waypoints, so corners stay clean.
  if (std::abs(heading_error_rad) > 0.35 || distance_m < 3.0 || speed_m_s_ < 0.5) return;
  const double u = random_.Uniform();
  const double p_stop = o_.stop_rate_per_s * dt_s_;
  const double p_side = o_.side_step_rate_per_s * dt_s_;
  const double p_back = o_.back_step_rate_per_s * dt_s_;
  if (u < p_stop) {
    mode_ = Mode::kStop;
    mode_end_s_ = t_s_ + random_.Uniform(o_.stop_min_s, o_.stop_max_s);
  } else if (u < p_stop + p_side) {
    const double side = random_.Bernoulli(0.5) ? 0.5 * kPi : -0.5 * kPi;
    TryDodge(heading_rad_ + side, o_.side_step_m);
  } else if (u < p_stop + p_side + p_back) {
    TryDodge(heading_rad_ + kPi, o_.back_step_m);
  }
}

bool Walker::TryDodge(double direction_rad, double distance_m) {
  const Vector2d direction = Direction(direction_rad);
  // The walker still drifts forward while braking; check the end point with that margin.
  const Vector2d end = position_ + distance_m * direction;
  for (const geometry::Segment2& wall : walls_) {
    const auto hit = geometry::RaySegmentIntersection(position_, direction, wall);
    if (hit && *hit < distance_m + o_.wall_clearance_m) return false;
    if (geometry::DistanceToSegment(wall, end) < o_.wall_clearance_m + 0.2) return false;
  }
  mode_ = Mode::kDodge;
  dodge_direction_ = direction;
  dodge_start_s_ = t_s_;
  dodge_duration_s_ = distance_m / o_.dodge_speed_m_s;
  dodge_peak_m_s_ = 0.5 * kPi * o_.dodge_speed_m_s;
  mode_end_s_ = t_s_ + dodge_duration_s_;
  return true;
}

void Walker::AdvanceGait(double moved_m) {
  const double speed = moved_m / dt_s_;
  const double step_length_m = o_.step_length_base_m + o_.step_length_per_speed_s * speed;
  const double before = std::floor(phase_);
  phase_ += moved_m / step_length_m;
  if (std::floor(phase_) > before) {
    motion_.step_end_indices.push_back(motion_.states.size());
    // A new amplitude only at a step end, where sin(pi * phase) is ~0: the yaw stays continuous.
    const double intensity = std::clamp(speed / std::max(spec_.cruise_speed_m_s, 0.3), 0.0, 1.1);
    sway_scale_ = intensity * std::clamp(random_.Normal(1.0, o_.sway_variation), 0.6, 1.15);
  }
}

double Walker::BendAngle() {
  if (!bend_.active && random_.Bernoulli(o_.bend_rate_per_s * dt_s_)) {
    bend_.active = true;
    bend_.start_s = t_s_;
    bend_.hold_s = random_.Uniform(0.3, o_.bend_hold_max_s);
    bend_.peak_rad = random_.Bernoulli(o_.bend_up_fraction)
                         ? -random_.Uniform(0.4 * o_.bend_up_max_rad, o_.bend_up_max_rad)
                         : random_.Uniform(o_.bend_down_min_rad, o_.bend_down_max_rad);
  }
  if (!bend_.active) return 0.0;
  const double tau = t_s_ - bend_.start_s;
  const double ramp = o_.bend_ramp_s;
  double shape = 1.0;
  if (tau < ramp) {
    shape = 0.5 * (1.0 - std::cos(kPi * tau / ramp));
  } else if (tau > ramp + bend_.hold_s) {
    const double back = tau - ramp - bend_.hold_s;
    if (back >= ramp) bend_.active = false;
    shape = 0.5 * (1.0 + std::cos(kPi * std::min(back / ramp, 1.0)));
  }
  return shape * bend_.peak_rad;
}

void Walker::Record(std::size_t index, const Vector2d& previous_position, double previous_yaw_rad) {
  TrueState state;
  state.stamp_s = SampleStamp(spec_.start_time_s, index, o_.rate_hz);
  const double yaw = BodyYaw();
  state.world_from_body = {position_.x(), position_.y(), geometry::NormalizeAngle(yaw)};
  const double gait = sway_scale_;
  state.pitch_rad = o_.pitch_lean_rad * std::min(gait, 1.0) +
                    gait * o_.pitch_sway_rad * std::sin(2.0 * kPi * phase_) + pitch_drift_rad_ +
                    BendAngle();
  state.roll_rad = gait * o_.roll_sway_rad * std::sin(kPi * phase_) + roll_drift_rad_;
  if (index > 0) {
    const Vector2d moved = position_ - previous_position;
    state.yaw_rate_rad_s = geometry::NormalizeAngle(yaw - previous_yaw_rad) / dt_s_;
    state.speed_m_s = moved.norm() / dt_s_;
    state.forward_velocity_m_s = moved.dot(Direction(yaw)) / dt_s_;
  }
  motion_.states.push_back(state);
}

}  // namespace

HumanMotion::HumanMotion(const HumanMotionOptions& options) : options_(options) {
  const auto& o = options;
  Require(o.rate_hz > 0.0, "rate_hz must be > 0 Hz, got " + std::to_string(o.rate_hz));
  Require(o.waypoint_tolerance_m > 0.0, "waypoint_tolerance_m must be > 0 m");
  Require(o.lookahead_m > 0.0, "lookahead_m must be > 0 m");
  Require(o.max_turn_rate_rad_s > 0.0, "max_turn_rate_rad_s must be > 0 rad/s");
  Require(o.turn_gain_per_s > 0.0, "turn_gain_per_s must be > 0 1/s");
  Require(o.max_turn_accel_rad_s2 > 0.0, "max_turn_accel_rad_s2 must be > 0 rad/s^2");
  Require(o.acceleration_m_s2 > 0.0 && o.deceleration_m_s2 > 0.0,
          "acceleration_m_s2 and deceleration_m_s2 must be > 0 m/s^2");
  Require(o.speed_change_time_s > 0.0 && o.tilt_drift_time_s > 0.0,
          "speed_change_time_s and tilt_drift_time_s must be > 0 s");
  Require(o.stop_min_s >= 0.0 && o.stop_max_s >= o.stop_min_s,
          "stop_min_s/stop_max_s out of order");
  Require(o.dodge_speed_m_s > 0.0, "dodge_speed_m_s must be > 0 m/s");
  Require(o.step_length_base_m > 0.0, "step_length_base_m must be > 0 m");
  Require(o.bend_ramp_s > 0.0 && o.bend_hold_max_s >= 0.3,
          "bend_ramp_s must be > 0 s, bend_hold_max_s >= 0.3 s");
  Require(o.bend_up_fraction >= 0.0 && o.bend_up_fraction <= 1.0,
          "bend_up_fraction must be in [0, 1]");
}

TrueMotion HumanMotion::Generate(const EntitySpec& spec,
                                 const std::vector<geometry::Segment2>& walls,
                                 Random& random) const {
  if (!(spec.cruise_speed_m_s > 0.0)) {
    throw std::invalid_argument("human_motion: entity " + spec.id +
                                " needs cruise_speed_m_s > 0 m/s");
  }
  Walker walker(options_, spec, walls, random);
  return walker.Run();
}

}  // namespace pena::sim
