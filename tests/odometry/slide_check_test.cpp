// The people's slide check on simulated missions (docs/odometry.md, "Estimator"): between
// keyframes, weakly constrained matches that fall back against the walk keep the spread strides'
// prior along the corridor, and a prior that a constraining match has just found off (a step
// back) is not kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "pena/dead_reckoning/stride_interpolator.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "expect_refused.hpp"
#include "team_entity.hpp"

namespace pena::odometry {
namespace {

sim::EntityRecording Office(std::uint64_t seed) {
  const sim::Scenario office = sim::ParseScenario(std::string(*sim::BuiltinScenarioText("office")), "builtin:office");
  sim::SimulationOptions options;
  options.seed = seed;
  return sim::Simulator(options).Run(office).entities.front();
}

// The estimates of the scans up to `until_s`, from the strides spread as the tools spread them.
std::vector<OdometryEstimate> Estimates(const sim::EntityRecording& entity, const LaserOdometryOptions& options,
                                        double until_s) {
  std::vector<sensors::SensorRecord> records;
  for (const sensors::SensorRecord& record : entity.records) {
    if (sensors::StampOf(record) > until_s) break;
    records.push_back(record);
  }
  records = dead_reckoning::SpreadStrides(std::move(records), dead_reckoning::SpreadOptionsOf(options.dead_reckoning));
  return testing::ReplayRecords(entity, records, options);
}

// The largest error along x (the corridor) over the scans in [from_s, to_s], and the largest jump
// of that error from one scan to the next.
struct AlongErrors {
  double max_m = 0.0;
  double max_step_m = 0.0;
};

AlongErrors Along(const sim::EntityRecording& entity, const std::vector<OdometryEstimate>& run, double from_s,
                  double to_s) {
  AlongErrors out;
  std::optional<double> previous;
  for (const OdometryEstimate& estimate : run) {
    if (estimate.stamp_s < from_s || estimate.stamp_s > to_s) continue;
    const auto truth = std::find_if(entity.truth.begin(), entity.truth.end(), [&](const sensors::GroundTruth& t) {
      return std::abs(t.stamp_s - estimate.stamp_s) < 1e-6;
    });
    if (truth == entity.truth.end()) continue;
    const double error = estimate.world_from_body.x_m - truth->world_from_body.x_m;
    out.max_m = std::max(out.max_m, std::abs(error));
    if (previous) out.max_step_m = std::max(out.max_step_m, std::abs(error - *previous));
    previous = error;
  }
  return out;
}

// Office seed 5 walking west along the main corridor at 104.5-106.5 s: without the check every
// other scan between keyframes was matched 0.3-0.45 m behind a prior that was right, and the
// output jumped back and forth by as much.
TEST(SlideCheck, HoldsAWalkersScansBetweenKeyframesToTheirPrior) {
  const sim::EntityRecording walker = Office(5);
  LaserOdometryOptions off;
  off.degenerate_slide_ratio = 0.0;
  off.degenerate_slide_backward_only = false;
  const AlongErrors checked = Along(walker, Estimates(walker, {}, 107.0), 104.5, 106.5);
  const AlongErrors unchecked = Along(walker, Estimates(walker, off, 107.0), 104.5, 106.5);
  EXPECT_LT(checked.max_step_m, 0.12) << "without the check " << unchecked.max_step_m << " m";
  EXPECT_GT(unchecked.max_step_m, 0.3);
}

// Team seed 1, ff1 at 14.5-15 s steps back while facing on: the stride model reads a step forward
// and the prior is 0.3 m off; the matches at 15.75-16.5 s are right and must not be held to it.
TEST(SlideCheck, LetsTheMatchesCorrectAPriorThatAConstrainingMatchFoundOff) {
  const sim::EntityRecording& ff1 = testing::TeamEntity("ff1");
  LaserOdometryOptions unchecked;
  unchecked.degenerate_slide_prior_agreed_m = 0.0;
  const AlongErrors checked = Along(ff1, Estimates(ff1, {}, 17.0), 15.75, 16.5);
  const AlongErrors held = Along(ff1, Estimates(ff1, unchecked, 17.0), 15.75, 16.5);
  EXPECT_LT(checked.max_m, 0.08) << "held to the prior: " << held.max_m << " m";
  EXPECT_GT(held.max_m, 0.15);
}

double MaxDifferenceM(const std::vector<OdometryEstimate>& a, const std::vector<OdometryEstimate>& b) {
  double max_m = a.size() == b.size() ? 0.0 : 1e9;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    max_m = std::max(max_m, std::hypot(a[i].world_from_body.x_m - b[i].world_from_body.x_m,
                                       a[i].world_from_body.y_m - b[i].world_from_body.y_m));
  }
  return max_m;
}

// `pena map` runs people with the long reference (kAutoLocalMapKeyframes): auto is
// the long one for a person, and it is a different run from the short default's.
TEST(LocalMapLength, AutoIsTheLongReferenceForPeopleAndBelowItIsRefusedNamingTheField) {
  const sim::EntityRecording walker = Office(5);
  LaserOdometryOptions automatic;
  automatic.local_map_keyframes = LaserOdometryOptions::kAutoLocalMapKeyframes;
  LaserOdometryOptions long_reference;
  long_reference.local_map_keyframes = LaserOdometryOptions::kLongLocalMapKeyframes;
  const std::vector<OdometryEstimate> by_auto = Estimates(walker, automatic, 40.0);
  EXPECT_EQ(MaxDifferenceM(by_auto, Estimates(walker, long_reference, 40.0)), 0.0);
  EXPECT_GT(MaxDifferenceM(by_auto, Estimates(walker, {}, 40.0)), 0.01);
  LaserOdometryOptions below;
  below.local_map_keyframes = -2;
  testing::ExpectRefused(below, "local_map_keyframes");
}

}  // namespace
}  // namespace pena::odometry
