// Where the odometry's time goes (LaserOdometry::stage_times(), pena/stage_clock.hpp): every
// stage a scan passes through is filled, each instant counts to one stage only, and the stages
// sum to no more than the time spent inside Add.
#include <gtest/gtest.h>

#include <chrono>
#include <variant>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "pena/stage_clock.hpp"
#include "team_entity.hpp"

namespace pena {
namespace {

using SteadyClock = std::chrono::steady_clock;

enum class Toy { kOuter, kInner, kRest, kCount };

void BusyFor(std::chrono::microseconds duration) {
  const SteadyClock::time_point until = SteadyClock::now() + duration;
  while (SteadyClock::now() < until) {
  }
}

// A stage inside another counts its own time; the outer one does not count it again.
TEST(StageClock, NestedStagesCountTheirTimeOnce) {
  StageClock<Toy> clock;
  {
    const StageClock<Toy>::Call call(clock, Toy::kRest);
    BusyFor(std::chrono::microseconds(2000));
    const StageClock<Toy>::Scope outer(clock, Toy::kOuter);
    BusyFor(std::chrono::microseconds(2000));
    {
      const StageClock<Toy>::Scope inner(clock, Toy::kInner);
      BusyFor(std::chrono::microseconds(3000));
    }
    BusyFor(std::chrono::microseconds(2000));
  }
  const StageTimes<Toy>& times = clock.times();
  EXPECT_EQ(times.total.calls, 1);
  EXPECT_EQ(times[Toy::kOuter].calls, 1);
  EXPECT_EQ(times[Toy::kInner].calls, 1);
  EXPECT_EQ(times[Toy::kRest].calls, 1);
  EXPECT_GE(times[Toy::kRest].seconds, 0.002);
  EXPECT_GE(times[Toy::kOuter].seconds, 0.004);
  EXPECT_GE(times[Toy::kInner].seconds, 0.003);
  // Exclusive: the parts add up to the whole (up to rounding), never more.
  EXPECT_NEAR(times.StagesSeconds(), times.total.seconds, 1e-9);
}

TEST(StageClock, MoveHandsACalleesOwnTimeToAnotherStage) {
  StageClock<Toy> clock;
  {
    const StageClock<Toy>::Call call(clock, Toy::kRest);
    const StageClock<Toy>::Scope outer(clock, Toy::kOuter);
    BusyFor(std::chrono::microseconds(3000));
    clock.Move(Toy::kInner, 0.001);
  }
  const StageTimes<Toy>& times = clock.times();
  EXPECT_EQ(times[Toy::kInner].calls, 1);
  EXPECT_DOUBLE_EQ(times[Toy::kInner].seconds, 0.001);
  EXPECT_GE(times[Toy::kOuter].seconds, 0.002);
  EXPECT_NEAR(times.StagesSeconds(), times.total.seconds, 1e-9);
}

}  // namespace

namespace odometry {
namespace {

struct Profiled {
  OdometryStageTimes times;
  OdometryCounts counts;
  long records = 0;
  double wall_s = 0.0;  // around the calls of Add, measured here
};

Profiled Profile(const sim::EntityRecording& entity, const std::vector<sensors::SensorRecord>& records) {
  LaserOdometry odometry({}, entity.kind, entity.truth.front().world_from_body, entity.start_s);
  Profiled run;
  const SteadyClock::time_point started = SteadyClock::now();
  for (const sensors::SensorRecord& record : records) {
    (void)odometry.Add(record);
    ++run.records;
  }
  run.wall_s = std::chrono::duration<double>(SteadyClock::now() - started).count();
  run.times = odometry.stage_times();
  run.counts = odometry.counts();
  return run;
}

void ExpectFilled(const Profiled& run, OdometryStage stage) {
  EXPECT_GT(run.times[stage].calls, 0) << ToString(stage);
  EXPECT_GT(run.times[stage].seconds, 0.0) << ToString(stage);
}

void ExpectConsistent(const Profiled& run) {
  EXPECT_EQ(run.times.total.calls, run.records);
  for (const StageTime& stage : run.times.stages) EXPECT_GE(stage.seconds, 0.0);
  EXPECT_LE(run.times.StagesSeconds(), run.times.total.seconds + 1e-9);
  EXPECT_LE(run.times.total.seconds, run.wall_s);
  // Most of Add's time is in named stages, not in the rest.
  EXPECT_LT(run.times[OdometryStage::kOther].seconds, 0.5 * run.times.total.seconds);
  EXPECT_EQ(run.times[OdometryStage::kPoints].calls, run.counts.scans);
  EXPECT_GE(run.times[OdometryStage::kReference].calls, run.counts.keyframes);
  // The search kept for each matched scan is refined once, grown windows and other priors not.
  EXPECT_EQ(run.times[OdometryStage::kRefinement].calls, run.counts.matched + run.counts.degenerate);
}

TEST(OdometryStageTimes, RobotScansFillEveryStageAndSumToNoMoreThanTheTotal) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  // Taken over 0.1 s each, so that deskew runs (the simulator's scans are instantaneous).
  std::vector<sensors::SensorRecord> records = robot.records;
  records.resize(records.size() * 2 / 5);  // the first part of the drive is enough
  for (sensors::SensorRecord& record : records) {
    if (auto* scan = std::get_if<sensors::LaserScan>(&record)) scan->geometry.sweep_s = 0.1;
  }
  const Profiled run = Profile(robot, records);
  ASSERT_GT(run.counts.scans, 100);
  ExpectConsistent(run);
  for (OdometryStage stage :
       {OdometryStage::kPrediction, OdometryStage::kPoints, OdometryStage::kDeskew,
        OdometryStage::kReference, OdometryStage::kSearchBase, OdometryStage::kRefinement,
        OdometryStage::kCovariance, OdometryStage::kKeyframePolicy}) {
    ExpectFilled(run, stage);
  }
  EXPECT_GE(run.times[OdometryStage::kSearchBase].calls + run.times[OdometryStage::kSearchWide].calls,
            run.counts.matched + run.counts.degenerate);
}

TEST(OdometryStageTimes, PeopleWithoutDeskewSpendNothingThere) {
  const sim::EntityRecording& firefighter = testing::TeamEntity("ff1");
  std::vector<sensors::SensorRecord> records = firefighter.records;
  records.resize(records.size() * 2 / 5);
  const Profiled run = Profile(firefighter, records);
  ASSERT_GT(run.counts.scans, 100);
  ExpectConsistent(run);
  ExpectFilled(run, OdometryStage::kPrediction);
  ExpectFilled(run, OdometryStage::kSearchBase);
  EXPECT_EQ(run.times[OdometryStage::kDeskew].calls, 0);
  EXPECT_EQ(run.times[OdometryStage::kDeskew].seconds, 0.0);
}

}  // namespace
}  // namespace odometry
}  // namespace pena
