// Statistics of the walking and driving models against the paper's figures for human motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "pena/sim/human_motion.hpp"
#include "pena/sim/robot_motion.hpp"
#include "sim_test_util.hpp"

namespace pena::sim {
namespace {

using testing::kDeg;

TrueMotion Walk(std::uint64_t seed, int laps = 3) {
  const Scenario scenario = testing::CorridorLoop(sensors::EntityKind::kHuman, laps);
  Random random(seed);
  return HumanMotion().Generate(scenario.entities[0], scenario.walls, random);
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Distance from a point to the route polyline (start, then the waypoints).
double DistanceToRoute(const EntitySpec& spec, const Eigen::Vector2d& point) {
  double best = 1e9;
  Eigen::Vector2d from(spec.start.x_m, spec.start.y_m);
  for (const Waypoint& waypoint : spec.route) {
    best = std::min(best, geometry::DistanceToSegment({from, waypoint.position_m}, point));
    from = waypoint.position_m;
  }
  return best;
}

TEST(HumanMotion, WalksAtAboutOneMetrePerSecond) {
  const TrueMotion motion = Walk(1);
  double sum = 0.0;
  int count = 0;
  for (const TrueState& state : motion.states) {
    if (state.speed_m_s > 0.3) {
      sum += state.speed_m_s;
      ++count;
    }
  }
  ASSERT_GT(count, 1000);
  EXPECT_NEAR(sum / count, 1.0, 0.15);
}

TEST(HumanMotion, StopsAndStepsAsideNowAndThen) {
  // Over a long walk the walker stops on straight stretches (away from every waypoint) and
  // steps sideways and backwards.
  const Scenario scenario = testing::CorridorLoop(sensors::EntityKind::kHuman, 6);
  const TrueMotion motion = Walk(2, 6);
  int stopped = 0, sideways = 0, backwards = 0;
  for (const TrueState& state : motion.states) {
    const Eigen::Vector2d p(state.world_from_body.x_m, state.world_from_body.y_m);
    double to_waypoint = 1e9;
    for (const Waypoint& waypoint : scenario.entities[0].route) {
      to_waypoint = std::min(to_waypoint, (waypoint.position_m - p).norm());
    }
    if (state.speed_m_s < 0.05 && to_waypoint > 1.5) ++stopped;
    const double lateral =
        std::sqrt(std::max(0.0, state.speed_m_s * state.speed_m_s -
                                    state.forward_velocity_m_s * state.forward_velocity_m_s));
    if (lateral > 0.4) ++sideways;
    if (state.forward_velocity_m_s < -0.2) ++backwards;
  }
  EXPECT_GT(stopped, 100);  // at least a second of standing
  EXPECT_GT(sideways, 20);
  EXPECT_GT(backwards, 20);
}

TEST(HumanMotion, YawSwaysTwentyToFortyDegreesPerSecondPerStep) {
  const TrueMotion motion = Walk(3);
  std::vector<double> peaks;
  std::size_t begin = 0;
  for (const std::size_t end : motion.step_end_indices) {
    double peak = 0.0;
    for (std::size_t i = begin + 1; i <= end; ++i) {
      peak = std::max(peak, std::abs(motion.states[i].yaw_rate_rad_s));
    }
    if (motion.states[end].speed_m_s > 0.7) peaks.push_back(peak);
    begin = end;
  }
  ASSERT_GT(peaks.size(), 100u);
  const double median_deg_s = Median(peaks) / kDeg;
  EXPECT_GE(median_deg_s, 20.0);
  EXPECT_LE(median_deg_s, 40.0);
}

TEST(HumanMotion, TurnsFastButNeverBeyondTwoHundredDegreesPerSecond) {
  double peak = 0.0;
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    for (const TrueState& state : Walk(seed).states) {
      peak = std::max(peak, std::abs(state.yaw_rate_rad_s));
    }
  }
  EXPECT_LE(peak, 200.0 * kDeg);
  EXPECT_GE(peak, 90.0 * kDeg);  // the corners are taken briskly
}

TEST(HumanMotion, PitchAndRollSwayByDegreesWithLargerBends) {
  const TrueMotion motion = Walk(5);
  double pitch_sum = 0, pitch_sq = 0, roll_sum = 0, roll_sq = 0, pitch_max = -1, pitch_min = 1;
  for (const TrueState& state : motion.states) {
    pitch_sum += state.pitch_rad;
    pitch_sq += state.pitch_rad * state.pitch_rad;
    roll_sum += state.roll_rad;
    roll_sq += state.roll_rad * state.roll_rad;
    pitch_max = std::max(pitch_max, state.pitch_rad);
    pitch_min = std::min(pitch_min, state.pitch_rad);
  }
  const double n = static_cast<double>(motion.states.size());
  const double pitch_sd = std::sqrt(pitch_sq / n - std::pow(pitch_sum / n, 2));
  const double roll_sd = std::sqrt(roll_sq / n - std::pow(roll_sum / n, 2));
  EXPECT_GT(pitch_sd, 1.0 * kDeg);
  EXPECT_LT(pitch_sd, 8.0 * kDeg);
  EXPECT_GT(roll_sd, 1.0 * kDeg);
  EXPECT_LT(roll_sd, 6.0 * kDeg);
  EXPECT_GT(pitch_max, 8.0 * kDeg);  // bends over
  EXPECT_LT(pitch_max, 35.0 * kDeg);
  EXPECT_LT(pitch_min, -3.0 * kDeg);  // looks up
}

TEST(HumanMotion, FollowsTheRouteAndFinishesWhereItEnds) {
  const Scenario scenario = testing::CorridorLoop(sensors::EntityKind::kHuman, 2);
  const TrueMotion motion = Walk(6, 2);
  for (const TrueState& state : motion.states) {
    const Eigen::Vector2d p(state.world_from_body.x_m, state.world_from_body.y_m);
    ASSERT_LT(DistanceToRoute(scenario.entities[0], p), 0.75) << "at t = " << state.stamp_s;
  }
  const geometry::Pose2& last = motion.states.back().world_from_body;
  EXPECT_LT(std::hypot(last.x_m - 1.0, last.y_m - 1.0), 0.2);
  // Two laps of 56 m at about 1 m/s plus pauses and corners.
  const double duration = motion.states.back().stamp_s - motion.states.front().stamp_s;
  EXPECT_GT(duration, 100.0);
  EXPECT_LT(duration, 180.0);
}

TEST(HumanMotion, StepsAreAboutHalfAMetre) {
  const TrueMotion motion = Walk(7);
  std::vector<double> lengths;
  std::size_t from = 0;
  for (const std::size_t to : motion.step_end_indices) {
    const auto& a = motion.states[from].world_from_body;
    const auto& b = motion.states[to].world_from_body;
    if (motion.states[to].speed_m_s > 0.8)
      lengths.push_back(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m));
    from = to;
  }
  ASSERT_GT(lengths.size(), 100u);
  EXPECT_NEAR(Median(lengths), 0.55, 0.07);
}

TEST(HumanMotion, RejectsANonPositiveRate) {
  HumanMotionOptions options;
  options.rate_hz = 0.0;
  EXPECT_THROW(HumanMotion{options}, std::invalid_argument);
}

TEST(RobotMotion, DrivesTheRouteLevelAtCruiseSpeed) {
  const Scenario scenario = testing::CorridorLoop(sensors::EntityKind::kRobot);
  const RobotMotionOptions options;
  const TrueMotion motion = RobotMotion(options).Generate(scenario.entities[0]);
  double peak_speed = 0.0, peak_rate = 0.0;
  for (const TrueState& state : motion.states) {
    ASSERT_EQ(state.pitch_rad, 0.0);
    ASSERT_EQ(state.roll_rad, 0.0);
    ASSERT_LT(DistanceToRoute(scenario.entities[0],
                              {state.world_from_body.x_m, state.world_from_body.y_m}),
              0.3);
    peak_speed = std::max(peak_speed, state.speed_m_s);
    peak_rate = std::max(peak_rate, std::abs(state.yaw_rate_rad_s));
  }
  EXPECT_NEAR(peak_speed, 0.5, 0.01);
  EXPECT_LE(peak_rate, options.max_yaw_rate_rad_s + 1e-12);
  const geometry::Pose2& last = motion.states.back().world_from_body;
  EXPECT_LT(std::hypot(last.x_m - 1.0, last.y_m - 1.0), options.waypoint_tolerance_m + 1e-9);
}

}  // namespace
}  // namespace pena::sim
