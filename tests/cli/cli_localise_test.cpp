// `pena localise --smooth` as a user runs it: the smoothed trajectory in trajectory.tum, the causal
// one in trajectory-online.tum (byte for byte what a run without the option writes), both scored
// in summary.json. Accuracy is not asserted here: docs/localisation.md, "Offline smoothing".
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

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

}  // namespace
}  // namespace pena::testing
