#include "pena/sim/robot_motion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::sim {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("robot_motion." + what);
}

TrueState MakeState(double stamp_s, const Eigen::Vector2d& position, double heading_rad,
                    double forward_m_s, double yaw_rate_rad_s) {
  TrueState state;
  state.stamp_s = stamp_s;
  state.world_from_body = {position.x(), position.y(), heading_rad};
  state.forward_velocity_m_s = forward_m_s;
  state.speed_m_s = std::abs(forward_m_s);
  state.yaw_rate_rad_s = yaw_rate_rad_s;
  return state;  // a robot's laser is level: pitch = roll = 0
}

}  // namespace

RobotMotion::RobotMotion(const RobotMotionOptions& options) : options_(options) {
  Require(options.rate_hz > 0.0, "rate_hz must be > 0 Hz, got " + std::to_string(options.rate_hz));
  Require(options.waypoint_tolerance_m > 0.0, "waypoint_tolerance_m must be > 0 m");
  Require(options.max_yaw_rate_rad_s > 0.0, "max_yaw_rate_rad_s must be > 0 rad/s");
  Require(options.turn_gain_per_s > 0.0, "turn_gain_per_s must be > 0 1/s");
  Require(options.acceleration_m_s2 > 0.0, "acceleration_m_s2 must be > 0 m/s^2");
}

TrueMotion RobotMotion::Generate(const EntitySpec& spec) const {
  const RobotMotionOptions& o = options_;
  if (!(spec.cruise_speed_m_s > 0.0)) {
    throw std::invalid_argument("robot_motion: entity " + spec.id +
                                " needs cruise_speed_m_s > 0 m/s");
  }
  const std::vector<Waypoint> route = UnrollRoute(spec);
  const double dt_s = 1.0 / o.rate_hz;
  TrueMotion motion;
  motion.rate_hz = o.rate_hz;
  Eigen::Vector2d position(spec.start.x_m, spec.start.y_m);
  double heading_rad = spec.start.theta_rad;
  double speed_m_s = 0.0;
  double hold_until_s = 0.0;  // waypoint pauses and the final stand
  std::size_t target = 0;
  double time_limit_s =
      120.0;  // ten times the cruise time plus pauses: beyond it the robot is stuck
  Eigen::Vector2d from = position;
  for (const Waypoint& waypoint : route) {
    time_limit_s +=
        10.0 * (waypoint.position_m - from).norm() / spec.cruise_speed_m_s + waypoint.pause_s;
    from = waypoint.position_m;
  }
  motion.states.push_back(MakeState(spec.start_time_s, position, heading_rad, 0.0, 0.0));
  for (std::size_t index = 1;; ++index) {
    const double t_s = static_cast<double>(index) * dt_s;
    double yaw_rate = 0.0;
    double wanted_speed = 0.0;
    if (target < route.size() && t_s >= hold_until_s) {
      const Eigen::Vector2d to_target = route[target].position_m - position;
      if (to_target.norm() < o.waypoint_tolerance_m) {
        hold_until_s = t_s + route[target].pause_s;
        if (++target == route.size()) hold_until_s += o.finish_stand_s;
      } else {
        const double error =
            geometry::NormalizeAngle(std::atan2(to_target.y(), to_target.x()) - heading_rad);
        yaw_rate =
            std::clamp(o.turn_gain_per_s * error, -o.max_yaw_rate_rad_s, o.max_yaw_rate_rad_s);
        // Turn in place when far off course; slow down near the waypoint to avoid orbiting it.
        const double alignment = std::max(0.0, std::cos(error));
        wanted_speed =
            spec.cruise_speed_m_s * alignment * alignment * std::min(1.0, 0.3 + to_target.norm());
      }
    } else if (target == route.size() && t_s >= hold_until_s) {
      break;
    }
    speed_m_s += std::clamp(wanted_speed - speed_m_s, -o.acceleration_m_s2 * dt_s,
                            o.acceleration_m_s2 * dt_s);
    // Exact arc integration of a unicycle over dt, so odometry built from (v, w) matches truth.
    const double dtheta = yaw_rate * dt_s;
    const double mid = heading_rad + 0.5 * dtheta;
    const double chord = std::abs(dtheta) > 1e-9
                             ? speed_m_s * dt_s * std::sin(0.5 * dtheta) / (0.5 * dtheta)
                             : speed_m_s * dt_s;
    position += chord * Eigen::Vector2d(std::cos(mid), std::sin(mid));
    heading_rad = geometry::NormalizeAngle(heading_rad + dtheta);
    motion.states.push_back(MakeState(SampleStamp(spec.start_time_s, index, o.rate_hz), position,
                                      heading_rad, speed_m_s, yaw_rate));
    if (t_s > time_limit_s)
      throw std::runtime_error("robot_motion: entity " + spec.id + " is stuck");
  }
  return motion;
}

}  // namespace pena::sim
