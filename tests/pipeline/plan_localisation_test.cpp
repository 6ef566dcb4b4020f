// Entity-side map localisation (pena-entity with a plan loaded; paper section 4.2): a firefighter
// whose compass is disturbed drifts on its own laser odometry; with the a priori plan set,
// EntityPipeline matches a virtual scan of the plan at every reference change and its published
// pose stays close to the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::pipeline {
namespace {

// The team building with ff1 alone, walking past three steel structures (the compass off by up
// to 40 deg there), as in tests/services_fusion/corrections_matter_test.cpp: the route ends at
// the central corridor (its last leg into the lobby ends with a laser-odometry failure that
// has nothing to do with the compass).
const sim::SimulationResult& Disturbed() {
  static const sim::SimulationResult result = [] {
    std::istringstream team{std::string(*sim::BuiltinScenarioText("team"))};
    std::ostringstream text;
    for (std::string line; std::getline(team, line);) {
      const bool entity_line = line.rfind("entity ", 0) == 0 || line.rfind("waypoint ", 0) == 0;
      if (entity_line && line.find(" ff1 ") == std::string::npos) continue;
      if (line == "waypoint ff1 23 3") continue;
      text << line << '\n';
    }
    text << "magnetic 16 9 5 40\nmagnetic 7 15 5 -40\nmagnetic 14 26 5 40\n";
    const sim::Scenario scenario = sim::ParseScenario(text.str(), "test:plan_localisation");
    return sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  }();
  return result;
}

const std::vector<geometry::Segment2>& Plan() {
  static const std::vector<geometry::Segment2> plan =
      *sim::ParseScenario(*sim::BuiltinScenarioText("team"), "builtin:team").apriori;
  return plan;
}

struct Errors {
  double published_rmse_m = 0.0;  // world_from_body (with the plan's corrections)
  double odometry_rmse_m = 0.0;   // the laser odometry alone (odom_from_body)
  PipelineCounts counts;
};

double SquaredDistance(const geometry::Pose2& a, const geometry::Pose2& b) {
  return (a.x_m - b.x_m) * (a.x_m - b.x_m) + (a.y_m - b.y_m) * (a.y_m - b.y_m);
}

Errors Replay(bool with_plan) {
  const sim::EntityRecording& ff1 = Disturbed().entities.front();
  EntityPipeline pipeline({}, ff1.kind, ff1.id, ff1.truth.front().world_from_body, ff1.start_s);
  if (with_plan) pipeline.SetPlan(Plan());
  double published = 0.0, odometry = 0.0;
  std::size_t scan = 0;
  const auto score = [&](const ScanStep& step) {
    EXPECT_NEAR(step.odometry.stamp_s, ff1.truth[scan].stamp_s, 1e-6);
    const geometry::Pose2& truth = ff1.truth[scan++].world_from_body;
    published += SquaredDistance(step.world_from_body, truth);
    odometry += SquaredDistance(step.odometry.world_from_body, truth);
  };
  for (const sensors::SensorRecord& record : ff1.records) {
    for (const ScanStep& step : pipeline.Add(record)) score(step);
  }
  pipeline.EndOfInput();
  while (const std::optional<ScanStep> step = pipeline.Next()) score(*step);
  EXPECT_EQ(scan, ff1.scans);
  return {std::sqrt(published / static_cast<double>(scan)),
          std::sqrt(odometry / static_cast<double>(scan)), pipeline.counts()};
}

TEST(PlanLocalisation, HalvesTheErrorOfAnEntityWhoseCompassIsDisturbed) {
  const Errors without = Replay(false);
  const Errors with = Replay(true);
  std::printf("[ figures  ] ff1 (disturbed compass) RMSE: odometry %.3f m, pipeline without plan "
              "%.3f m, with plan %.3f m (%ld rounds, %ld corrections)\n",
              without.odometry_rmse_m, without.published_rmse_m, with.published_rmse_m,
              with.counts.plan_rounds, with.counts.plan_corrections);
  // Without a plan (and without fusion corrections) the published pose is the odometry's.
  EXPECT_NEAR(without.published_rmse_m, without.odometry_rmse_m, 1e-9);
  EXPECT_EQ(without.counts.plan_rounds, 0);
  // The odometry does not depend on the plan: corrections only move map_from_odom.
  EXPECT_NEAR(with.odometry_rmse_m, without.odometry_rmse_m, 1e-9);
  ASSERT_GT(without.odometry_rmse_m, 0.3) << "the scenario no longer makes ff1 drift";
  EXPECT_LE(with.published_rmse_m, 0.5 * without.odometry_rmse_m);
  EXPECT_GT(with.counts.plan_corrections, 0);
}

TEST(PlanLocalisation, RefusesAnEmptyPlanOrBadOptions) {
  const sim::EntityRecording& ff1 = Disturbed().entities.front();
  EntityPipeline pipeline({}, ff1.kind, ff1.id, ff1.truth.front().world_from_body, ff1.start_s);
  EXPECT_THROW(pipeline.SetPlan({}), std::invalid_argument);
  EXPECT_FALSE(pipeline.has_plan());
  EntityPipelineOptions options;
  options.plan_localisation.map.min_hits = 0;
  EntityPipeline bad(options, ff1.kind, ff1.id, ff1.truth.front().world_from_body, ff1.start_s);
  try {
    bad.SetPlan(Plan());
    FAIL() << "min_hits 0 accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("min_hits"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace pena::pipeline
