// The covariance every OdometryEstimate carries (PoseCovarianceOptions), against the simulated
// team's ground truth: it must hold the true error without being uselessly wide.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"

namespace pena::odometry {
namespace {

constexpr double kChiSquare2Dof99 = 9.210;  // 99 % of a consistent 2-D error lies within

// e^T P^-1 e of the position error (NEES); nullopt where P is singular (the start).
std::optional<double> PositionNees(const OdometryEstimate& estimate, const geometry::Pose2& truth) {
  const Eigen::Matrix2d p = estimate.covariance.topLeftCorner<2, 2>();
  if (!(p.determinant() > 0.0)) return std::nullopt;
  const Eigen::Vector2d error(estimate.world_from_body.x_m - truth.x_m,
                              estimate.world_from_body.y_m - truth.y_m);
  return error.dot(p.ldlt().solve(error));
}

struct Consistency {
  double inside_99 = 0.0;  // share of scans whose error lies within the 99 % ellipse
  double mean_nees = 0.0;  // 2 when the covariance is right
};

Consistency Measure(const sim::EntityRecording& entity) {
  const std::vector<OdometryEstimate> estimates =
      testing::ReplayRecords(entity, entity.records, LaserOdometryOptions{});
  if (estimates.size() != entity.truth.size()) throw std::runtime_error("one estimate per scan");
  Consistency out;
  int counted = 0;
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    const std::optional<double> nees = PositionNees(estimates[i], entity.truth[i].world_from_body);
    if (!nees) continue;
    ++counted;
    out.inside_99 += *nees <= kChiSquare2Dof99 ? 1.0 : 0.0;
    out.mean_nees += *nees;
  }
  out.inside_99 /= counted;
  out.mean_nees /= counted;
  return out;
}

TEST(OdometryCovariance, StartsAtZeroAndStaysSymmetricPositiveSemiDefinite) {
  for (const std::string id : {"ff1", "robot1"}) {
    const sim::EntityRecording& entity = testing::TeamEntity(id);
    const std::vector<OdometryEstimate> estimates =
        testing::ReplayRecords(entity, entity.records, LaserOdometryOptions{});
    ASSERT_FALSE(estimates.empty());
    EXPECT_TRUE(estimates.front().covariance.isZero()) << id;
    for (const OdometryEstimate& estimate : estimates) {
      const Eigen::Matrix3d& p = estimate.covariance;
      ASSERT_TRUE(p.allFinite()) << id << " at " << estimate.stamp_s;
      ASSERT_TRUE(p.isApprox(p.transpose(), 1e-9) || p.isZero())
          << id << " at " << estimate.stamp_s;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(p).eigenvalues().minCoeff(), -1e-12)
          << id << " at " << estimate.stamp_s;
    }
    // Odometry closes no loops: it ends less certain than it started.
    EXPECT_GT(estimates.back().covariance.trace(),
              estimates[estimates.size() / 10].covariance.trace())
        << id;
  }
}

// Measured on team seed 1 with the defaults: inside 1.00 / 1.00 / 1.00 / 1.00 of the 99 %
// ellipses, mean NEES 0.59 / 1.73 / 1.10 for the people and 0.03 for the robot, whose simulated
// laser is ideal (on the real Freiburg logs its NEES is 1.1-2.8, docs/odometry.md).
TEST(OdometryCovariance, HoldsTheTrueErrorOfEveryTeamMember) {
  for (const std::string id : {"ff1", "ff2", "ff3", "robot1"}) {
    const Consistency c = Measure(testing::TeamEntity(id));
    EXPECT_GE(c.inside_99, 0.95) << id << ": overconfident, mean NEES " << c.mean_nees;
    if (id != "robot1") {
      EXPECT_GE(c.mean_nees, 0.25) << id << ": more than eight times too cautious";
    }
  }
}

// Without a usable scan the pose comes from dead reckoning alone: the covariance grows with the
// walk from the keyframe the prior is anchored at, and still holds the true error.
TEST(OdometryCovariance, GrowsWithTheWalkWhileNoScanCanBeMatched) {
  const sim::EntityRecording& firefighter = testing::TeamEntity("ff1");
  constexpr int kFirstBlind = 100;
  constexpr int kBlindScans = 40;  // 10 s of walking
  std::vector<sensors::SensorRecord> records;
  int scans = 0;
  for (const sensors::SensorRecord& record : firefighter.records) {
    sensors::SensorRecord fed = record;
    if (auto* scan = std::get_if<sensors::LaserScan>(&fed)) {
      ++scans;
      if (scans > kFirstBlind && scans <= kFirstBlind + kBlindScans) {
        std::fill(scan->ranges_m.begin(), scan->ranges_m.end(), sensors::LaserScan::kNoReturn);
      }
    }
    records.push_back(fed);
  }
  const std::vector<OdometryEstimate> estimates =
      testing::ReplayRecords(firefighter, records, LaserOdometryOptions{});
  const OdometryEstimate& before = estimates[kFirstBlind - 1];
  const OdometryEstimate& last_blind = estimates[kFirstBlind + kBlindScans - 1];
  ASSERT_EQ(last_blind.status, MatchStatus::kNoPoints);
  const double walked_m = std::hypot(last_blind.world_from_body.x_m - before.world_from_body.x_m,
                                     last_blind.world_from_body.y_m - before.world_from_body.y_m);
  ASSERT_GT(walked_m, 3.0);
  const double added_m2 = last_blind.covariance.topLeftCorner<2, 2>().trace() -
                          before.covariance.topLeftCorner<2, 2>().trace();
  // At least the motion prior's drift over the walk (0.05 m / sqrt(m) on each axis).
  const PoseCovarianceOptions defaults;
  EXPECT_GE(added_m2, 2.0 * defaults.motion_m_per_sqrt_m * defaults.motion_m_per_sqrt_m * walked_m);
  const std::optional<double> nees =
      PositionNees(last_blind, firefighter.truth[kFirstBlind + kBlindScans - 1].world_from_body);
  ASSERT_TRUE(nees.has_value());
  EXPECT_LE(*nees, kChiSquare2Dof99);
}

TEST(OdometryCovariance, InvalidOptionNamesField) {
  LaserOdometryOptions options;
  options.covariance.match_residual_sd_m = 0.0;
  try {
    LaserOdometry odometry(options, sensors::EntityKind::kHuman, {}, 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("covariance.match_residual_sd_m"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::odometry
