// `pena localise` as a user runs it: plan adaptation's outputs, and `--smooth`: the smoothed trajectory in trajectory.tum, the causal
// one in trajectory-online.tum (byte for byte what a run without the option writes), both scored
// in summary.json. Accuracy is not asserted here: docs/localisation.md, "Offline smoothing".
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "pena/io/line_csv.hpp"
#include "pena/io/trajectory_io.hpp"
#include "run_pena.hpp"

namespace pena::testing {
namespace {

TEST(CliLocalise, SmoothWritesTheSmoothedAndTheCausalTrajectory) {
  const auto mission = FreshDir("loc_smooth_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 2 --out " + mission.string()).exit_code, 0);
  const std::string inputs = "localise --quiet --log " +
                             (mission / "ff1" / "sensors.penalog").string() + " --map " +
                             (mission / "apriori.csv").string();
  const auto causal = FreshDir("loc_causal_out");
  const auto smoothed = FreshDir("loc_smooth_out");
  const PenaRun plain = RunPena(inputs + " --out " + causal.string());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const PenaRun smooth = RunPena(inputs + " --out " + smoothed.string() + " --smooth");
  ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
  EXPECT_FALSE(std::filesystem::exists(causal / "trajectory-online.tum"));
  EXPECT_EQ(ReadBytes(smoothed / "trajectory-online.tum"), ReadBytes(causal / "trajectory.tum"));
  EXPECT_EQ(ReadBytes(smoothed / "status.csv"), ReadBytes(causal / "status.csv"));
  const geometry::Trajectory online = io::ReadTum(smoothed / "trajectory-online.tum");
  const geometry::Trajectory estimate = io::ReadTum(smoothed / "trajectory.tum");
  ASSERT_EQ(estimate.size(), online.size());
  EXPECT_NE(ReadBytes(smoothed / "trajectory.tum"), ReadBytes(causal / "trajectory.tum"));
  const std::string summary = ReadBytes(smoothed / "summary.json");
  EXPECT_NE(summary.find("\"smoothed\": true, \"truth_online\": {"), std::string::npos) << summary;
  EXPECT_EQ(ReadBytes(causal / "summary.json").find("truth_online"), std::string::npos);
  EXPECT_NE(smooth.out.find("causal (trajectory-online.tum)"), std::string::npos) << smooth.out;
}

// Distance from a segment's midpoint to the nearest of `walls`.
double MidpointToNearest(const geometry::Segment2& s, const std::vector<io::LineRow>& walls) {
  const Eigen::Vector2d mid = 0.5 * (s.start_m + s.end_m);
  double best = 1e9;
  for (const io::LineRow& w : walls) best = std::min(best, geometry::DistanceToSegment(w.segment, mid));
  return best;
}

// The office plan draws some walls 0.3-0.6 m off: the walls pena localise moves must end up
// nearer the true ones (floorplan.csv), listed in plan-shifts.csv and summary.json.
// (The openings it cuts are checked on their own below: here they are off.)
TEST(CliLocalise, PlanAdaptationMovesDrawnOffWallsTowardsTheTrueOnes) {
  const auto mission = FreshDir("loc_adapt_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 2 --out " + mission.string()).exit_code, 0);
  const std::string inputs = "localise --quiet --log " + (mission / "ff1" / "sensors.penalog").string() +
                             " --map " + (mission / "apriori.csv").string() +
                             " --set plan_adaptation.openings.enabled=0";
  const auto adapted = FreshDir("loc_adapt_out");
  const PenaRun run = RunPena(inputs + " --out " + adapted.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("plan adaptation: "), std::string::npos) << run.out;
  const std::vector<io::LineRow> drawn = io::ReadLineCsv(mission / "apriori.csv");
  const std::vector<io::LineRow> after = io::ReadLineCsv(adapted / "plan-adapted.csv");
  const std::vector<io::LineRow> walls = io::ReadLineCsv(mission / "floorplan.csv");
  ASSERT_EQ(after.size(), drawn.size());
  const std::string shifts = ReadBytes(adapted / "plan-shifts.csv");
  const long moved = std::count(shifts.begin(), shifts.end(), '\n') - 1;
  EXPECT_GE(moved, 2) << shifts;
  long changed = 0;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    if (after[i].segment.start_m == drawn[i].segment.start_m && after[i].segment.end_m == drawn[i].segment.end_m) continue;
    ++changed;
    EXPECT_GT(MidpointToNearest(drawn[i].segment, walls), 0.25) << "segment " << i << " was drawn right";
    EXPECT_LT(MidpointToNearest(after[i].segment, walls), 0.05) << "segment " << i;
  }
  EXPECT_EQ(changed, moved);
  EXPECT_NE(ReadBytes(adapted / "summary.json").find("\"plan_shifts\": [{\"id\": "), std::string::npos);
  const auto off = FreshDir("loc_adapt_off");
  ASSERT_EQ(RunPena(inputs + " --out " + off.string() + " --set plan_adaptation.enabled=0").exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(off / "plan-adapted.csv"));
  EXPECT_NE(ReadBytes(off / "summary.json").find("\"plan_shifts\": []"), std::string::npos);
}

// The office plan draws the passage at x 22 and the corridor's west end shut: pena localise cuts
// them open where the rounds see through (plan-openings.csv), and no real wall.
TEST(CliLocalise, PlanAdaptationCutsOpeningsTheDrawingClosed) {
  const auto mission = FreshDir("loc_open_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 2 --out " + mission.string()).exit_code, 0);
  const auto out = FreshDir("loc_open_out");
  const PenaRun run = RunPena("localise --quiet --log " + (mission / "ff1" / "sensors.penalog").string() +
                              " --map " + (mission / "apriori.csv").string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("opening(s) cut"), std::string::npos) << run.out;
  const std::vector<io::LineRow> drawn = io::ReadLineCsv(mission / "apriori.csv");
  const std::vector<io::LineRow> walls = io::ReadLineCsv(mission / "floorplan.csv");
  std::istringstream cuts(ReadBytes(out / "plan-openings.csv"));
  std::string line;
  std::getline(cuts, line);
  EXPECT_EQ(line, "id,from_m,to_m,rounds,added_id");
  int on_drawn = 0, added = 0;
  while (std::getline(cuts, line)) {
    std::istringstream fields(line);
    std::string id, from, to, rounds, added_id;
    std::getline(fields, id, ',');
    std::getline(fields, from, ',');
    std::getline(fields, to, ',');
    std::getline(fields, rounds, ',');
    std::getline(fields, added_id, ',');
    added += std::stoi(added_id) >= 0 ? 1 : 0;
    const auto index = static_cast<std::size_t>(std::stoi(id));
    if (index >= drawn.size()) continue;  // a part appended by an earlier cut
    ++on_drawn;
    const geometry::Segment2& s = drawn[index].segment;
    const Eigen::Vector2d along = (s.end_m - s.start_m).normalized();
    const geometry::Segment2 stretch{s.start_m + std::stod(from) * along, s.start_m + std::stod(to) * along};
    // No true wall runs along the drawn one there, even drawn 0.6 m off (the passage's own
    // walls meet it across).
    const Eigen::Vector2d mid = 0.5 * (stretch.start_m + stretch.end_m);
    for (const io::LineRow& w : walls) {
      const Eigen::Vector2d d = w.segment.end_m - w.segment.start_m;
      const double length_m = d.norm();
      if (std::abs(d.x() * along.y() - d.y() * along.x()) / length_m > 0.17) continue;  // not parallel
      const Eigen::Vector2d rel = mid - w.segment.start_m;
      const double on_m = rel.dot(d) / length_m;
      const double across_m = std::abs(rel.x() * d.y() - rel.y() * d.x()) / length_m;
      EXPECT_FALSE(on_m > 0.0 && on_m < length_m && across_m < 0.6) << "cut a real wall: " << line;
    }
  }
  EXPECT_GE(on_drawn, 2);
  EXPECT_EQ(io::ReadLineCsv(out / "plan-adapted.csv").size(), drawn.size() + static_cast<std::size_t>(added));
  EXPECT_NE(ReadBytes(out / "summary.json").find("\"plan_openings\": [{\"id\": "), std::string::npos);
}

TEST(CliLocalise, ASmootherSettingWithoutSmoothIsAClearError) {
  const PenaRun run =
      RunPena("localise --log x.penalog --map x.csv --out x --set smooth.round_sigma_m=0.1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find("needs --smooth"), std::string::npos) << run.err;
}

TEST(CliLocalise, AnUnknownSmootherSettingIsAClearError) {
  const PenaRun run =
      RunPena("localise --log x.penalog --map x.csv --out x --smooth --set smooth.nonsense=1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find("smooth.nonsense"), std::string::npos) << run.err;
}

// Lost and found's outputs: the `lost` column of status.csv and `lost_intervals` in summary.json
// (an office walk from its known start is never lost); a bad lost.* value is a clear error.
TEST(CliLocalise, ReportsLostIntervalsAndRefusesBadLostOptions) {
  const auto mission = FreshDir("loc_lost_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 1 --out " + mission.string()).exit_code, 0);
  const std::string inputs = "localise --quiet --log " + (mission / "ff1" / "sensors.penalog").string() +
                             " --map " + (mission / "apriori.csv").string();
  const auto out = FreshDir("loc_lost_out");
  const PenaRun run = RunPena(inputs + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string status = ReadBytes(out / "status.csv");
  EXPECT_NE(status.find(",ends_corrected,lost\n"), std::string::npos);
  EXPECT_NE(ReadBytes(out / "summary.json").find("\"lost_intervals\": []"), std::string::npos);
  const PenaRun bad = RunPena(inputs + " --out " + out.string() + " --set lost.region_growth=0.5");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("lost_and_found.region_growth must be >= 1, got 0.5"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace pena::testing
