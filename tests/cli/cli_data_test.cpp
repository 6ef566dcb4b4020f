// `pena info`, `pena export` and `pena eval` on the real Freiburg logs and on broken inputs.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>

#include "run_pena.hpp"

namespace pena::testing {
namespace {

// A CARMEN FLASER line with `beams` ranges of 2 m at `stamp_s` (odometry at the origin).
std::string FlaserLine(int beams, double stamp_s, const std::string& first_range = "2.0") {
  std::string line = "FLASER " + std::to_string(beams) + " " + first_range;
  for (int i = 1; i < beams; ++i) line += " 2.0";
  const std::string stamp = std::to_string(stamp_s);
  return line + " 0 0 0 0 0 0 " + stamp + " host " + stamp + "\n";
}

std::filesystem::path WriteText(const std::string& name, const std::string& text) {
  const auto path = FreshDir("cli_" + name) / name;
  std::ofstream(path) << text;
  return path;
}

// Expects a failed run with exactly one error line naming `file` and `line`.
void ExpectOneLineError(const PenaRun& run, const std::string& file, int line) {
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find(file + ":" + std::to_string(line) + ":"), std::string::npos) << run.err;
}

TEST(CliInfo, SummarisesMitCsailLog) {
  const PenaRun run = RunPena("info " + DataPath("freiburg/mit-csail.clf.gz").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("1988"), std::string::npos) << run.out;  // scans
  EXPECT_NE(run.out.find("361"), std::string::npos) << run.out;   // beams
}

TEST(CliInfo, TooFewRangesNamesFileAndLine) {
  const auto path =
      WriteText("short.clf", FlaserLine(181, 1.0) + FlaserLine(181, 1.25) + "FLASER 181 1.0 2.0\n");
  ExpectOneLineError(RunPena("info " + path.string()), "short.clf", 3);
}

TEST(CliInfo, NanRangeNamesFileAndLine) {
  const auto path = WriteText("nan.clf", FlaserLine(181, 1.0) + FlaserLine(181, 1.25, "nan"));
  ExpectOneLineError(RunPena("info " + path.string()), "nan.clf", 2);
}

TEST(CliInfo, SkipMalformedCountsAndKeepsGoodLines) {
  const auto path = WriteText("skip.clf", FlaserLine(181, 1.0) + FlaserLine(181, 1.25, "nan") +
                                              FlaserLine(181, 1.5));
  const PenaRun run = RunPena("info --skip-malformed " + path.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(std::regex_search(run.out, std::regex("skipped[^\\n]*1"))) << run.out;
}

TEST(CliInfo, TruncatedGzipNamesFileAndLine) {
  const auto dir = FreshDir("cli_truncated");
  const auto full = dir / "full.clf.gz";
  gzFile gz = gzopen(full.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  for (int i = 0; i < 400; ++i) {
    const std::string line = FlaserLine(181, 1.0 + 0.25 * i);
    gzwrite(gz, line.data(), static_cast<unsigned>(line.size()));
  }
  gzclose(gz);
  const std::string bytes = ReadBytes(full);
  const auto cut = dir / "cut.clf.gz";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const PenaRun run = RunPena("info " + cut.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_TRUE(std::regex_search(run.err, std::regex("cut\\.clf\\.gz:[0-9]+:"))) << run.err;
}

TEST(CliInfo, MissingFileIsAnError) {
  const PenaRun run = RunPena("info /nonexistent/pena.clf");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("/nonexistent/pena.clf"), std::string::npos) << run.err;
}

// data/README.md: raw odometry scores about 1.7 m on mit-csail (7.4 m intel, 0.55 m aces).
TEST(CliEval, ReproducesRawOdometryFigureOnMitCsail) {
  const auto dir = FreshDir("cli_eval_mit");
  const auto tum = dir / "odometry.tum";
  const PenaRun exported =
      RunPena("export --log " + DataPath("freiburg/mit-csail.clf.gz").string() + " --tum " +
              tum.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const PenaRun run = RunPena("eval --json --trajectory " + tum.string() + " --relations " +
                              DataPath("freiburg/mit-csail.relations").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      run.out, match, std::regex("\"translational_error_m\"[^}]*?\"mean\"\\s*:\\s*([0-9.eE+-]+)")))
      << run.out;
  const double mean_m = std::stod(match[1]);
  EXPECT_GT(mean_m, 1.5);
  EXPECT_LT(mean_m, 1.9);
}

// A perturbed log: the odometry in the scans' pose fields carries the noise model's errors, ODOM
// lines are left out, stamps that do not advance (orebro: all 0) are restamped, and --tum keeps
// the poses as read. The same seed gives the same log; the truth scored against itself is exact.
TEST(CliExport, PerturbedOdometryIsSeededRestampedAndScoredAgainstTheTruth) {
  const auto dir = FreshDir("cli_export_perturb");
  const std::string log = DataPath("radish-corrected/orebro-corrected.log.gz").string();
  const auto export_seed = [&](const std::string& name, int seed) {
    return RunPena("export --log " + log + " --carmen " + (dir / name).string() +
                   " --perturb-odometry " + std::to_string(seed) + " --tum " +
                   (dir / (name + ".tum")).string());
  };
  const PenaRun first = export_seed("a.clf", 4);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("restamped 236 scans"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("odometry perturbed (seed 4)"), std::string::npos) << first.out;
  ASSERT_EQ(export_seed("b.clf", 4).exit_code, 0);
  ASSERT_EQ(export_seed("c.clf", 5).exit_code, 0);
  const std::string a = ReadBytes(dir / "a.clf");
  EXPECT_EQ(a, ReadBytes(dir / "b.clf"));
  EXPECT_NE(a, ReadBytes(dir / "c.clf"));
  EXPECT_EQ(a.find("ODOM"), std::string::npos);
  // The truth has every scan once, in increasing time; the perturbed odometry is off it.
  const PenaRun self = RunPena("eval --json --trajectory " + (dir / "a.clf.tum").string() +
                               " --truth " + (dir / "a.clf.tum").string());
  ASSERT_EQ(self.exit_code, 0) << self.err;
  EXPECT_EQ(JsonNumber(self.out, "matched"), 237.0);
  EXPECT_EQ(JsonNumber(self.out, "translation_rmse_m"), 0.0);
  const auto odometry = dir / "odometry.tum";
  ASSERT_EQ(RunPena("export --log " + (dir / "a.clf").string() + " --tum " + odometry.string())
                .exit_code,
            0);
  const PenaRun off = RunPena("eval --json --trajectory " + odometry.string() + " --truth " +
                              (dir / "a.clf.tum").string());
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_GT(JsonNumber(off.out, "final_heading_error_deg"), 1.0);
  // Perturbing needs a CARMEN output to carry the odometry.
  EXPECT_NE(RunPena("export --log " + log + " --tum " + (dir / "x.tum").string() +
                    " --perturb-odometry 1")
                .exit_code,
            0);
}

// The line map's tolerances. A segment 15 cm off its wall is covered at 20 cm, not at the issue's
// 10 cm; a segment turned 7 deg about a point of its wall is covered at 10 deg, not at 5 deg. The
// JSON and the table say which tolerances judged the map.
TEST(CliEval, LineToleranceOptionsChangeTheMatchAndAreReported) {
  const auto walls = WriteText("walls.csv", "id,x1,y1,x2,y2\n0,0,0,4,0\n");
  const auto off = WriteText("off.csv", "id,x1,y1,x2,y2\n0,0,0.15,4,0.15\n");
  const std::string base = "eval --json --walls " + walls.string() + " --lines ";
  const PenaRun strict = RunPena(base + off.string());
  ASSERT_EQ(strict.exit_code, 0) << strict.err;
  EXPECT_EQ(JsonNumber(strict.out, "coverage"), 0.0) << strict.out;
  EXPECT_EQ(JsonNumber(strict.out, "distance_tolerance_m"), 0.1) << strict.out;
  EXPECT_EQ(JsonNumber(strict.out, "angle_tolerance_deg"), 10.0) << strict.out;
  const PenaRun wide = RunPena(base + off.string() + " --distance-tolerance 0.2");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NEAR(JsonNumber(wide.out, "coverage"), 1.0, 1e-9) << wide.out;
  EXPECT_NEAR(JsonNumber(wide.out, "precision"), 1.0, 1e-9) << wide.out;
  EXPECT_EQ(JsonNumber(wide.out, "distance_tolerance_m"), 0.2) << wide.out;

  // 1 m at 7 deg through (2, 0): within 10 cm of the wall for 0.82 m of it either way.
  const double half = 0.5, angle = 7.0 * std::numbers::pi / 180.0;
  const auto turned = WriteText(
      "turned.csv", "id,x1,y1,x2,y2\n0," + std::to_string(2 - half * std::cos(angle)) + "," +
                        std::to_string(-half * std::sin(angle)) + "," +
                        std::to_string(2 + half * std::cos(angle)) + "," +
                        std::to_string(half * std::sin(angle)) + "\n");
  const PenaRun at10 = RunPena(base + turned.string());
  ASSERT_EQ(at10.exit_code, 0) << at10.err;
  EXPECT_GT(JsonNumber(at10.out, "coverage"), 0.2) << at10.out;
  const PenaRun at5 = RunPena(base + turned.string() + " --angle-tolerance 5");
  ASSERT_EQ(at5.exit_code, 0) << at5.err;
  EXPECT_EQ(JsonNumber(at5.out, "coverage"), 0.0) << at5.out;
  EXPECT_EQ(JsonNumber(at5.out, "angle_tolerance_deg"), 5.0) << at5.out;

  const std::string table = "eval --walls " + walls.string() + " --lines " + off.string();
  const PenaRun defaults = RunPena(table);
  ASSERT_EQ(defaults.exit_code, 0) << defaults.err;
  EXPECT_NE(defaults.out.find("wall within 10 cm and 10 deg"), std::string::npos) << defaults.out;
  const PenaRun widened = RunPena(table + " --distance-tolerance 0.25 --angle-tolerance 12.5");
  ASSERT_EQ(widened.exit_code, 0) << widened.err;
  EXPECT_NE(widened.out.find("wall within 25 cm and 12.5 deg"), std::string::npos) << widened.out;
}

TEST(CliEval, BadLineToleranceIsAnErrorNamingTheOptionAndUnit) {
  const auto walls = WriteText("walls_bad.csv", "id,x1,y1,x2,y2\n0,0,0,4,0\n");
  const std::string base = "eval --lines " + walls.string() + " --walls " + walls.string();
  for (const char* value : {"0", "-0.1", "inf", "abc", "0.2abc"}) {
    const PenaRun run = RunPena(base + " --distance-tolerance " + value);
    EXPECT_NE(run.exit_code, 0) << value;
    const std::string expected =
        "--distance-tolerance: must be a distance > 0 m, got '" + std::string(value) + "'";
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  }
  for (const char* value : {"95", "-1", "nan"}) {
    const PenaRun run = RunPena(base + " --angle-tolerance " + value);
    EXPECT_NE(run.exit_code, 0) << value;
    const std::string expected =
        "--angle-tolerance: must be an angle in [0, 90] deg, got '" + std::string(value) + "'";
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  }
}

}  // namespace
}  // namespace pena::testing
