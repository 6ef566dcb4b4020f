// Returns that move with the walker (odometry::internal::WalkerFixedPoints): a bend's floor line
// across a corridor is dropped, the walls are kept.
#include "../../libpena/src/odometry/walker_fixed_points.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 2 m wide corridor along +x (walls at y = +-1 m from x = 0 to 30 m) with a door recess in the
// left wall (x 12-13 m, 0.5 m deep, its two faces across the corridor: static along-track
// features 2-3 m ahead of the scans below) and an end wall at x = 30 m.
std::vector<geometry::Segment2> Corridor() {
  return {{{0.0, -1.0}, {30.0, -1.0}},  {{0.0, 1.0}, {12.0, 1.0}},   {{12.0, 1.0}, {12.0, 1.5}},
          {{12.0, 1.5}, {13.0, 1.5}},   {{13.0, 1.5}, {13.0, 1.0}},  {{13.0, 1.0}, {30.0, 1.0}},
          {{30.0, -1.0}, {30.0, 1.0}}};
}

// Distance along the ray from `origin` in `direction` (unit) to the segment; nullopt if missed.
std::optional<double> RayHitM(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                              const geometry::Segment2& wall) {
  const Eigen::Vector2d edge = wall.end_m - wall.start_m;
  const double denominator = direction.x() * edge.y() - direction.y() * edge.x();
  if (std::abs(denominator) < 1e-12) return std::nullopt;
  const Eigen::Vector2d to_start = wall.start_m - origin;
  const double t = (to_start.x() * edge.y() - to_start.y() * edge.x()) / denominator;
  const double u = (to_start.x() * direction.y() - to_start.y() * direction.x()) / denominator;
  if (t <= 0.0 || u < 0.0 || u > 1.0) return std::nullopt;
  return t;
}

// A 180 deg scan at 0.5 deg beams (laser frame, beam order) from `x_m` on the corridor's axis,
// heading +x. With floor_line_m, a laser pitched down hits the floor on the line x = floor_line_m
// ahead (laser frame) wherever the beam gets there before a wall.
scan_matching::Points2 Scan(double x_m, std::optional<double> floor_line_m) {
  scan_matching::Points2 points;
  const Eigen::Vector2d origin(x_m, 0.0);
  for (int beam = 0; beam <= 360; ++beam) {
    const double angle = (-90.0 + 0.5 * beam) * kDeg;
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    double range = std::numeric_limits<double>::infinity();
    for (const auto& wall : Corridor()) {
      if (const auto hit = RayHitM(origin, direction, wall)) range = std::min(range, *hit);
    }
    if (floor_line_m && direction.x() > 0.0) range = std::min(range, *floor_line_m / direction.x());
    if (std::isfinite(range)) points.push_back(range * direction);
  }
  return points;
}

bool OnTheFloorLine(const Eigen::Vector2d& point, double floor_line_m) {
  return std::abs(point.x() - floor_line_m) < 1e-6 && std::abs(point.y()) < 1.0 - 1e-6;
}

// The previous scan 0.3 m back along the corridor (the motion prior is exact).
const geometry::Pose2 kWalked{0.3, 0.0, 0.0};

TEST(WalkerFixedPoints, DropsAFloorLineThatKeepsItsDistanceAndKeepsTheWalls) {
  const scan_matching::Points2 previous = Scan(10.0, 4.5);
  const scan_matching::Points2 current = Scan(10.3, 4.5);
  const std::vector<bool> moving = WalkerFixedPoints({}).Find(previous, current, kWalked);
  int line = 0, line_dropped = 0, walls_dropped = 0;
  for (std::size_t i = 0; i < current.size(); ++i) {
    if (OnTheFloorLine(current[i], 4.5)) {
      ++line;
      line_dropped += moving[i] ? 1 : 0;
    } else if (moving[i]) {
      ++walls_dropped;
      // Only the strips of side wall the line hid from the previous scan (within the 0.3 m walked
      // of the line's ends) can look the same: new, and beside a previous return.
      EXPECT_GT(current[i].x(), 4.5 - 0.3 - 1e-6) << current[i].transpose();
    }
  }
  EXPECT_GT(line, 20);
  EXPECT_EQ(line_dropped, line);
  EXPECT_LE(walls_dropped, 4);
  // The recess faces across the corridor 2-3 m ahead stay: they are where the walk puts them.
  const scan_matching::Points2 kept = WithoutMarked(current, moving);
  int recess_faces = 0;
  for (const auto& point : kept) recess_faces += point.y() > 1.0 + 1e-6 ? 1 : 0;
  EXPECT_GT(recess_faces, 5);
}

TEST(WalkerFixedPoints, DropsTheLineWhileThePitchBobMovesIt) {
  // The gait's pitch bob moves the line by up to about 1 m between scans at a 15 deg bend.
  const scan_matching::Points2 previous = Scan(10.0, 4.5);
  const scan_matching::Points2 current = Scan(10.3, 5.2);
  const std::vector<bool> moving = WalkerFixedPoints({}).Find(previous, current, kWalked);
  int line = 0, line_dropped = 0;
  for (std::size_t i = 0; i < current.size(); ++i) {
    if (!OnTheFloorLine(current[i], 5.2)) continue;
    ++line;
    line_dropped += moving[i] ? 1 : 0;
  }
  EXPECT_GT(line, 20);
  EXPECT_EQ(line_dropped, line);
}

TEST(WalkerFixedPoints, KeepsEveryStaticReturnWhenTheWalkerMoves) {
  const std::vector<bool> moving =
      WalkerFixedPoints({}).Find(Scan(10.0, std::nullopt), Scan(10.3, std::nullopt), kWalked);
  EXPECT_EQ(std::count(moving.begin(), moving.end(), true), 0);
}

TEST(WalkerFixedPoints, DropsNothingWithoutMotion) {
  // Standing still, everything is where it was in both frames: nothing can be told apart.
  const scan_matching::Points2 scan = Scan(10.0, 4.5);
  const WalkerFixedPoints filter({});
  const std::vector<bool> standing = filter.Find(scan, scan, {});
  EXPECT_EQ(std::count(standing.begin(), standing.end(), true), 0);
  // Nor below min_forward_m (0.15 m) along the heading, nor sideways (a side step).
  const std::vector<bool> slow = filter.Find(Scan(10.0, 4.5), Scan(10.1, 4.5), {0.1, 0.0, 0.0});
  EXPECT_EQ(std::count(slow.begin(), slow.end(), true), 0);
  const std::vector<bool> side = filter.Find(scan, scan, {0.0, 0.3, 0.0});
  EXPECT_EQ(std::count(side.begin(), side.end(), true), 0);
}

TEST(WalkerFixedPoints, DropsNothingInATurn) {
  // Turning faster than max_turn_rad (0.1 rad a scan) the walker slows and the prior overstates
  // the motion: the same walk with a 10 deg turn in the prior is left alone.
  const std::vector<bool> turning =
      WalkerFixedPoints({}).Find(Scan(10.0, 4.5), Scan(10.3, 4.5), {0.3, 0.0, 10.0 * kDeg});
  EXPECT_EQ(std::count(turning.begin(), turning.end(), true), 0);
}

TEST(WalkerFixedPoints, DropsOnlyRunsOfNeighbouringReturns) {
  // A short floor line 4.5 m ahead that only four neighbouring beams see.
  scan_matching::Points2 line;
  for (int i = 0; i < 4; ++i) line.emplace_back(4.5, 0.04 * i);
  const scan_matching::Points2& previous = line;
  const scan_matching::Points2& current = line;
  WalkerFixedPointsOptions options;
  options.max_fraction = 1.0;  // all of this scan is the line
  const std::vector<bool> runs = WalkerFixedPoints(options).Find(previous, current, kWalked);
  EXPECT_EQ(std::count(runs.begin(), runs.end(), true), 0);  // shorter than min_run_points (5)
  options.min_run_points = 3;
  const std::vector<bool> shorter = WalkerFixedPoints(options).Find(previous, current, kWalked);
  EXPECT_EQ(std::count(shorter.begin(), shorter.end(), true), 4);
}

TEST(WalkerFixedPoints, DropsNothingWhenThePriorMovedButTheWalkerStood) {
  // A stop the prior has not seen: every wall across the heading looks body-fixed. More than
  // max_fraction of the scan would go, so the prior is taken for the culprit.
  scan_matching::Points2 scan;
  for (int i = -20; i <= 20; ++i) scan.emplace_back(2.0, 0.05 * i);  // a wall 2 m ahead
  for (int i = 0; i < 20; ++i) scan.emplace_back(-1.0 + 0.15 * i, 1.0);  // a side wall
  WalkerFixedPointsOptions options;
  const std::vector<bool> guarded = WalkerFixedPoints(options).Find(scan, scan, kWalked);
  EXPECT_EQ(std::count(guarded.begin(), guarded.end(), true), 0);
  options.max_fraction = 1.0;
  const std::vector<bool> unguarded = WalkerFixedPoints(options).Find(scan, scan, kWalked);
  EXPECT_GE(std::count(unguarded.begin(), unguarded.end(), true), 41);  // the wall ahead
}

TEST(WalkerFixedPoints, OptionsNameTheFieldAndUnit) {
  WalkerFixedPointsOptions options;
  options.static_m = 0.0;
  EXPECT_THROW(WalkerFixedPoints{options}, std::invalid_argument);
  options = {};
  options.min_forward_m = options.static_m;
  try {
    WalkerFixedPoints filter(options);
    FAIL() << "min_forward_m = static_m accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "walker_fixed_points.min_forward_m must be > static_m (m), got 0.12");
  }
  options = {};
  options.max_fraction = 0.0;
  EXPECT_THROW(WalkerFixedPoints{options}, std::invalid_argument);
  options = {};
  options.body_along_m = -1.0;
  EXPECT_THROW(WalkerFixedPoints{options}, std::invalid_argument);
}

}  // namespace
}  // namespace pena::odometry::internal
