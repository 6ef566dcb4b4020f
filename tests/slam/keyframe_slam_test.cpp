// The keyframe SLAM on a simulated corridor loop walked 1.3 times with a drifting heading.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pena/sim/laser_raycaster.hpp"
#include "pena/slam/keyframe_slam.hpp"

namespace pena::slam {
namespace {

using geometry::Pose2;
using geometry::Segment2;

// A 2 m wide corridor around a 8 m x 4 m block, with niches so no stretch is featureless.
std::vector<Segment2> CorridorLoop() {
  std::vector<Segment2> walls;
  auto box = [&](double x0, double y0, double x1, double y1) {
    walls.push_back({{x0, y0}, {x1, y0}});
    walls.push_back({{x1, y0}, {x1, y1}});
    walls.push_back({{x1, y1}, {x0, y1}});
    walls.push_back({{x0, y1}, {x0, y0}});
  };
  box(-1.0, -1.0, 11.0, 7.0);  // outer walls
  box(1.0, 1.0, 9.0, 5.0);     // the block
  box(3.0, -1.0, 3.4, -0.6);   // pillars and cabinets along the walls
  box(6.5, 6.5, 7.3, 7.0);
  box(10.5, 2.5, 11.0, 3.2);
  box(-1.0, 4.0, -0.6, 4.3);
  box(5.0, 1.0, 5.5, 1.3);
  return walls;
}

// The corridor's centre line: (0,0) -> (10,0) -> (10,6) -> (0,6) -> (0,0), 0.1 m per step.
std::vector<Pose2> Walk(double laps) {
  const Eigen::Vector2d corners[] = {{0, 0}, {10, 0}, {10, 6}, {0, 6}};
  std::vector<Pose2> poses;
  const double lap_m = 32.0;
  for (double s = 0.0; s <= laps * lap_m; s += 0.1) {
    double along = std::fmod(s, lap_m);
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d a = corners[side];
      const Eigen::Vector2d b = corners[(side + 1) % 4];
      const double length = (b - a).norm();
      if (along <= length + 1e-9) {
        const Eigen::Vector2d p = a + (b - a) * (along / length);
        poses.push_back({p.x(), p.y(), std::atan2(b.y() - a.y(), b.x() - a.x())});
        break;
      }
      along -= length;
    }
  }
  return poses;
}

sensors::LaserScan Scan(const sim::LaserRaycaster& raycaster, const Pose2& pose, double stamp_s) {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = {-std::numbers::pi / 2.0, std::numbers::pi / 360.0, 30.0};
  sim::LaserPose laser;
  laser.position_m = {pose.x_m, pose.y_m, 1.0};
  laser.yaw_rad = pose.theta_rad;
  for (int i = 0; i < 361; ++i) {
    const sim::BeamHit hit = raycaster.Cast(laser, scan.BeamAngle(static_cast<std::size_t>(i)), 30.0);
    scan.ranges_m.push_back(hit.kind == sim::HitKind::kWall ? static_cast<float>(hit.range_m)
                                                            : sensors::LaserScan::kNoReturn);
  }
  return scan;
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

// The corridor loop walked 1.3 times with a heading drift of 0.34 deg per metre (11 deg per lap).
struct DriftedLoop {
  SlamCounts counts;
  SlamStageTimes stage_times;
  long calls = 0;         // of Add and Finish
  double wall_s = 0.0;    // around them, measured here
  std::vector<LoopClosureRecord> closures;
  std::vector<Pose2> truth;  // scan i at stamp 0.1 i s
  double odometry_error_m = 0.0;  // at the end
  double final_m = 0.0;           // corrected, at the end
  double worst_m = 0.0;           // corrected, anywhere
};

// The odometry turns `heading_drift_rad` too far per 0.1 m step, and slips `slip_m` forward at
// scan kSlipScan (x = 1 m on the second lap, 33 s).
constexpr std::size_t kSlipScan = 330;

DriftedLoop RunDriftedLoop(const SlamOptions& options, double heading_drift_rad = 0.0006,
                           double slip_m = 0.0) {
  const sim::LaserRaycaster raycaster(CorridorLoop(), 3.0);
  const std::vector<Pose2> truth = Walk(1.3);
  KeyframeSlam slam(options);
  Pose2 odometry = truth.front();
  DriftedLoop run;
  double inside_s = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) {
      Pose2 motion = geometry::Between(truth[i - 1], truth[i]);
      if (i == kSlipScan) motion.x_m += slip_m;
      motion.theta_rad += heading_drift_rad;
      odometry = geometry::Compose(odometry, motion);
    }
    run.odometry_error_m = Distance(odometry, truth[i]);
    const sensors::LaserScan scan = Scan(raycaster, truth[i], 0.1 * static_cast<double>(i));
    const auto started = std::chrono::steady_clock::now();
    slam.Add(scan, odometry);
    inside_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ++run.calls;
  }
  const auto started = std::chrono::steady_clock::now();
  slam.Finish();
  run.wall_s = inside_s + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ++run.calls;
  run.stage_times = slam.stage_times();
  const geometry::Trajectory corrected = slam.Trajectory();
  EXPECT_EQ(corrected.size(), truth.size());
  for (std::size_t i = 0; i < truth.size() && i < corrected.size(); ++i) {
    run.worst_m = std::max(run.worst_m, Distance(corrected[i].pose, truth[i]));
  }
  run.final_m = Distance(corrected.back().pose, truth.back());
  run.counts = slam.counts();
  run.closures = slam.closures();
  run.truth = truth;
  return run;
}

TEST(KeyframeSlam, ClosesTheLoopAndRemovesTheHeadingDrift) {
  const DriftedLoop run = RunDriftedLoop({});
  EXPECT_GT(run.odometry_error_m, 1.0);
  EXPECT_GE(run.counts.loop_closures, 1);
  EXPECT_LT(run.final_m, 0.15);
  EXPECT_LT(run.worst_m, 0.5);
}

// closures() lists each match that reached the graph: the kept ones measure their keyframes'
// true relative pose, which the drifted odometry (the graph's prior) had wrong.
// Where the SLAM's time goes: each loop check is one narrow or wide match, each solve one
// optimisation; the stages sum to no more than the time inside Add and Finish.
TEST(KeyframeSlam, StageTimesCountEveryCheckAndSolveAndSumToNoMoreThanTheTotal) {
  SlamOptions options;
  options.loop_wide_min_path_m = 20.0;
  options.loop_wide_window_m = 1.8;
  const DriftedLoop run = RunDriftedLoop(options, 0.0, 1.5);
  const SlamStageTimes& t = run.stage_times;
  ASSERT_GT(run.counts.wide_checks, 0);
  EXPECT_EQ(t.total.calls, run.calls);
  EXPECT_EQ(t[SlamStage::kKeyframes].calls, run.counts.keyframes);
  EXPECT_EQ(t[SlamStage::kLoopMatch].calls + t[SlamStage::kWideMatch].calls, run.counts.loop_checks);
  EXPECT_GT(t[SlamStage::kWideMatch].calls, 0);
  EXPECT_EQ(t[SlamStage::kOptimisation].calls, run.counts.optimisations);
  EXPECT_GT(t[SlamStage::kSubmapBuild].calls, 0);
  for (SlamStage stage : {SlamStage::kKeyframes, SlamStage::kCandidates, SlamStage::kSubmapBuild,
                          SlamStage::kLoopMatch, SlamStage::kWideMatch, SlamStage::kOptimisation}) {
    EXPECT_GT(t[stage].seconds, 0.0) << ToString(stage);
  }
  for (const StageTime& stage : t.stages) EXPECT_GE(stage.seconds, 0.0);
  EXPECT_LE(t.StagesSeconds(), t.total.seconds + 1e-9);
  EXPECT_LE(t.total.seconds, run.wall_s);
}

TEST(KeyframeSlam, ClosureRecordsMeasureTheTrueRelativePose) {
  const DriftedLoop run = RunDriftedLoop({});
  ASSERT_EQ(static_cast<long>(run.closures.size()), run.counts.loop_matched);
  long kept = 0;
  double worst_prior_m = 0.0;
  for (const LoopClosureRecord& c : run.closures) {
    ASSERT_LT(c.older_stamp_s, c.stamp_s);
    const auto index = [](double stamp_s) { return static_cast<std::size_t>(std::lround(stamp_s / 0.1)); };
    ASSERT_LT(index(c.stamp_s), run.truth.size());
    const Pose2 truth = geometry::Between(run.truth[index(c.older_stamp_s)], run.truth[index(c.stamp_s)]);
    EXPECT_GT(c.window_half_m, 0.0);
    if (!c.kept) continue;
    ++kept;
    EXPECT_LT(Distance(c.older_from_new, truth), 0.1) << "closure at " << c.stamp_s << " s";
    worst_prior_m = std::max(worst_prior_m, Distance(c.older_from_new_prior, truth));
  }
  EXPECT_EQ(kept, run.counts.loop_closures);
  EXPECT_GT(worst_prior_m, 0.3);  // the first closure corrected the drift
}

// At the revisit the drifted heading (11 deg) puts the best pose on the 5 deg window's heading
// edge: the heading search is widened, and without room to widen the loop stays open.
TEST(KeyframeSlam, AHeadingDriftBeyondTheWindowIsFoundByAWiderHeadingSearch) {
  SlamOptions no_room;
  no_room.loop_wide_window_m = 0.0;  // the narrow window alone
  no_room.loop_window_rad_per_m = 0.0;
  no_room.loop_window_max_rad = no_room.loop_window_rad;
  const DriftedLoop narrow = RunDriftedLoop(no_room);
  EXPECT_EQ(narrow.counts.loop_closures, 0);
  EXPECT_GT(narrow.final_m, 1.0);
  const DriftedLoop widened = RunDriftedLoop({});
  EXPECT_GT(widened.counts.loop_closures, 0);
  EXPECT_LT(widened.final_m, 0.15);
}

// Odometry that slips 1 m forward along the corridor on the second lap, heading kept: with a
// 0.2 m window each revisit after the slip has its best pose on the position edge, and such a
// match (a cut-off slope; in a corridor, often an alias) is refused rather than closed 0.2 m at a
// time. A window that holds the slip closes the loop.
TEST(KeyframeSlam, RefusesAMatchOnThePositionEdgeOfTheWindow) {
  const auto after_slip = [](const DriftedLoop& run) {
    long kept = 0;
    for (const LoopClosureRecord& c : run.closures) kept += c.kept && c.stamp_s > 0.1 * kSlipScan;
    return kept;
  };
  SlamOptions narrow_window;
  narrow_window.loop_wide_window_m = 0.0;  // the narrow window alone
  narrow_window.loop_window_per_m = 0.0;
  narrow_window.loop_window_max_m = narrow_window.loop_window_m;
  const DriftedLoop narrow = RunDriftedLoop(narrow_window, 0.0, 0.4);
  EXPECT_GT(narrow.odometry_error_m, 0.35);
  EXPECT_GT(narrow.counts.loop_checks, 10);
  EXPECT_EQ(after_slip(narrow), 0);
  EXPECT_GT(narrow.final_m, 0.35);
  SlamOptions wide_window = narrow_window;
  wide_window.loop_window_m = 1.5;
  wide_window.loop_window_max_m = 1.5;
  const DriftedLoop wide = RunDriftedLoop(wide_window, 0.0, 0.4);
  EXPECT_GT(after_slip(wide), 0);
  EXPECT_LT(wide.final_m, 0.5 * narrow.final_m);
}

// A slip of 1.5 m, far beyond the narrow window, which closures on the first lap keep small: the
// revisit a lap later is found in the wide window, and the loop closes. Without the wide window
// it stays open. (The window is 1.8 m here: 2 m off the truth, with the scan's origin inside
// the block, which no submap keyframe saw, the corridor scan fits the block's outer walls, an
// alias no test of the submap can refute.)
TEST(KeyframeSlam, AFarRevisitIsClosedInTheWideWindow) {
  SlamOptions options;
  options.loop_wide_min_path_m = 20.0;  // the loop is 32 m; a building's are longer
  options.loop_wide_window_m = 1.8;
  const DriftedLoop wide = RunDriftedLoop(options, 0.0, 1.5);
  SlamOptions narrow_only = options;
  narrow_only.loop_wide_window_m = 0.0;
  const DriftedLoop narrow = RunDriftedLoop(narrow_only, 0.0, 1.5);
  EXPECT_GT(narrow.final_m, 1.0);
  EXPECT_GT(wide.counts.wide_checks, 0);
  EXPECT_LT(wide.final_m, 0.5 * narrow.final_m);
}

TEST(KeyframeSlam, TheWideWindowIsOnForRobotsAndOffForPeopleUnlessSet) {
  EXPECT_EQ(ForEntity({}, sensors::EntityKind::kRobot).loop_wide_window_m, SlamOptions::kRobotWideWindowM);
  EXPECT_EQ(ForEntity({}, sensors::EntityKind::kHuman).loop_wide_window_m, 0.0);
  SlamOptions set;
  set.loop_wide_window_m = 2.5;
  EXPECT_EQ(ForEntity(set, sensors::EntityKind::kHuman).loop_wide_window_m, 2.5);
  // A person on the same drifted loop: no wide check is tried.
  const sim::LaserRaycaster raycaster(CorridorLoop(), 3.0);
  KeyframeSlam person(SlamOptions{}, sensors::EntityKind::kHuman);
  const std::vector<Pose2> truth = Walk(1.3);
  Pose2 odometry = truth.front();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) odometry = geometry::Compose(odometry, geometry::Between(truth[i - 1], truth[i]));
    if (i == kSlipScan) odometry.x_m += 1.5;
    person.Add(Scan(raycaster, truth[i], 0.1 * static_cast<double>(i)), odometry);
  }
  EXPECT_EQ(person.counts().wide_checks, 0);
}

TEST(KeyframeSlam, KeepsTheOdometryWhenNothingIsRevisited) {
  const sim::LaserRaycaster raycaster(CorridorLoop(), 3.0);
  const std::vector<Pose2> truth = Walk(0.5);
  KeyframeSlam slam;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Pose2 corrected = slam.Add(Scan(raycaster, truth[i], 0.1 * static_cast<double>(i)),
                                     truth[i]);
    EXPECT_LT(Distance(corrected, truth[i]), 1e-6);
  }
  EXPECT_EQ(slam.counts().loop_closures, 0);
}

TEST(KeyframeSlam, RefusesOptionsNamingTheField) {
  SlamOptions keyframe_distance;
  keyframe_distance.keyframe_distance_m = -1.0;
  SlamOptions weak_sigma_cap;
  weak_sigma_cap.loop_weak_sigma_max_m = -0.1;
  const std::pair<SlamOptions, std::string> cases[] = {
      {keyframe_distance, "slam.keyframe_distance_m"},
      {weak_sigma_cap, "slam.loop_weak_sigma_max_m"}};
  for (const auto& [options, field] : cases) {
    try {
      KeyframeSlam slam(options);
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace pena::slam
