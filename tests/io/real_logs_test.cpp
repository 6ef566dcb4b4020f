// The real logs of data/ read fully in strict mode (see data/README.md for the counts).
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <set>

#include "io_test_util.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/trajectory_io.hpp"

namespace pena::io {
namespace {

using sensors::LaserScan;

// Independent count of lines starting with "FLASER " (plain zlib, no parsing).
std::size_t CountFlaserLines(const std::filesystem::path& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  EXPECT_NE(file, nullptr);
  std::array<char, 1 << 16> buffer{};
  std::size_t count = 0;
  bool at_line_start = true;
  while (gzgets(file, buffer.data(), static_cast<int>(buffer.size())) != nullptr) {
    if (at_line_start && std::strncmp(buffer.data(), "FLASER ", 7) == 0) ++count;
    at_line_start = std::strchr(buffer.data(), '\n') != nullptr;
  }
  gzclose(file);
  return count;
}

struct LogSummary {
  std::size_t scans = 0;
  std::size_t odometry = 0;
  std::set<std::size_t> beam_counts;
  std::set<double> scan_stamps;
  std::size_t skipped = 0;
};

LogSummary Summarise(const std::filesystem::path& path) {
  LogSummary summary;
  auto source = OpenLog(path);  // strict: any malformed line or backwards time throws
  while (auto record = source->Next()) {
    if (const auto* scan = std::get_if<LaserScan>(&*record)) {
      ++summary.scans;
      summary.beam_counts.insert(scan->ranges_m.size());
      summary.scan_stamps.insert(scan->stamp_s);
    } else {
      ++summary.odometry;
    }
  }
  summary.skipped = source->skipped();
  return summary;
}

// True if a scan stamp lies within 6 us of `stamp_s`.
bool IsScanStamp(const std::set<double>& stamps, double stamp_s) {
  constexpr double kTolerance_s = 6e-6;
  const auto next = stamps.lower_bound(stamp_s - kTolerance_s);
  return next != stamps.end() && *next <= stamp_s + kTolerance_s;
}

struct FreiburgCase {
  const char* name;
  std::size_t scans;  // from data/README.md
  std::size_t beams;
};

class FreiburgLog : public ::testing::TestWithParam<FreiburgCase> {};

TEST_P(FreiburgLog, ReadsFullyInStrictModeWithReadmeScanCount) {
  const auto path = pena::testing::DataPath(std::string("freiburg/") + GetParam().name + ".clf.gz");
  const LogSummary summary = Summarise(path);
  EXPECT_EQ(summary.scans, GetParam().scans);
  EXPECT_EQ(summary.scans, CountFlaserLines(path));
  EXPECT_EQ(summary.beam_counts, std::set<std::size_t>{GetParam().beams});
  EXPECT_EQ(summary.skipped, 0u);
  // The README: relation stamps are scan stamps (mit-csail's relations round them to 10 us).
  const auto relations =
      ReadRelations(pena::testing::DataPath(std::string("freiburg/") + GetParam().name + ".relations"));
  ASSERT_FALSE(relations.empty());
  const std::size_t matched = static_cast<std::size_t>(
      std::count_if(relations.begin(), relations.end(), [&](const geometry::Relation& r) {
        return IsScanStamp(summary.scan_stamps, r.t1_s) && IsScanStamp(summary.scan_stamps, r.t2_s);
      }));
  EXPECT_EQ(matched, relations.size());
}

INSTANTIATE_TEST_SUITE_P(Datasets, FreiburgLog,
                         ::testing::Values(FreiburgCase{"intel", 13631, 180},
                                           FreiburgCase{"aces", 7374, 180},
                                           FreiburgCase{"mit-csail", 1988, 361}),
                         [](const auto& case_info) {
                           std::string name = case_info.param.name;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

class RadishLog : public ::testing::TestWithParam<const char*> {};

TEST_P(RadishLog, ReadsCleanlyInStrictMode) {
  const auto path = pena::testing::DataPath(std::string("radish-corrected/") + GetParam() + "-corrected.log.gz");
  const LogSummary summary = Summarise(path);
  EXPECT_GT(summary.scans, 0u);
  // Only radish intel has scans stepping back in time (4, by up to 0.86 s): dropped and counted.
  const std::size_t early = std::string(GetParam()) == "intel" ? 4u : 0u;
  EXPECT_EQ(summary.scans + early, CountFlaserLines(path));
  EXPECT_EQ(summary.skipped, early);
  ASSERT_EQ(summary.beam_counts.size(), 1u);
  const std::size_t beams = *summary.beam_counts.begin();
  EXPECT_TRUE(beams == 180 || beams == 181 || beams == 361) << beams;
}

INSTANTIATE_TEST_SUITE_P(Datasets, RadishLog,
                         ::testing::Values("aces", "csail", "intel", "orebro", "seattle"));

}  // namespace
}  // namespace pena::io
