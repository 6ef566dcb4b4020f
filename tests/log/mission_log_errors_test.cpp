// What the native mission log does with bad files and bad input: cut, corrupt, foreign, misused.
#include <gtest/gtest.h>

#include <stdexcept>

#include "log_test_util.hpp"
#include "pena/io/mission_log.hpp"

namespace pena::io {
namespace {

using testing::MakeHeader;
using testing::TempPath;

// The message of the InputError that opening `path` throws, or "" if it opens.
std::string OpenError(const std::filesystem::path& path) {
  try {
    MissionLogReader reader(path);
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 0u) << "header problems concern the whole file";
    return error.what();
  }
  return "";
}

std::vector<sensors::SensorRecord> ManyRecords() {
  std::vector<sensors::SensorRecord> records;
  for (int i = 0; i < 3; ++i) {
    for (auto& record : testing::MakeOneOfEach(1.0 * i)) records.push_back(record);
  }
  return records;
}

TEST(MissionLogErrors, CutFileGivesEveryWholeRecordThenNamesTheCutRecord) {
  const auto full = TempPath("full.penalog");
  const auto cut = TempPath("cut.penalog");
  const auto records = ManyRecords();
  testing::WriteLog(full, MakeHeader(), records);
  const std::string bytes = testing::ReadBytes(full);

  std::size_t clean_ends = 0;
  std::size_t previous_count = 0;
  for (std::size_t size = 0; size < bytes.size(); size += 7) {
    testing::WriteBytes(cut, bytes.substr(0, size));
    std::unique_ptr<MissionLogReader> reader;
    try {
      reader = std::make_unique<MissionLogReader>(cut);
    } catch (const InputError& error) {
      EXPECT_EQ(error.line(), 0u);  // cut inside the preamble or the header
      continue;
    }
    std::string error;
    const auto read = testing::ReadAll(*reader, &error);
    ASSERT_GE(read.size(), previous_count) << "a longer prefix never yields fewer records";
    ASSERT_LE(read.size(), records.size());
    for (std::size_t i = 0; i < read.size(); ++i) testing::ExpectSameRecord(records[i], read[i]);
    if (error.empty()) {
      ++clean_ends;  // the cut fell exactly between two records
    } else {
      const std::string where = ":" + std::to_string(read.size() + 1) + ": record " +
                                std::to_string(read.size() + 1) + " at byte offset ";
      EXPECT_NE(error.find(where), std::string::npos) << error;
      EXPECT_NE(error.find("truncated record"), std::string::npos) << error;
    }
    previous_count = read.size();
  }
  EXPECT_GT(previous_count, records.size() / 2);
  EXPECT_LT(clean_ends, records.size());  // most cuts land inside a record
}

TEST(MissionLogErrors, CutAtEveryByteOfTheLastRecordIsReported) {
  const auto full = TempPath("full.penalog");
  const auto cut = TempPath("cut.penalog");
  const auto records = ManyRecords();
  testing::WriteLog(full, MakeHeader(), records);
  const std::string bytes = testing::ReadBytes(full);
  testing::WriteLog(full, MakeHeader(), {records.begin(), records.end() - 1});
  const std::size_t last_start = std::filesystem::file_size(full);

  for (std::size_t size = last_start; size <= bytes.size(); ++size) {
    testing::WriteBytes(cut, bytes.substr(0, size));
    MissionLogReader reader(cut);
    std::string error;
    const auto read = testing::ReadAll(reader, &error);
    const bool whole = size == last_start || size == bytes.size();
    EXPECT_EQ(error.empty(), whole) << "cut at " << size << ": " << error;
    EXPECT_EQ(read.size(), size == bytes.size() ? records.size() : records.size() - 1);
  }
}

TEST(MissionLogErrors, CutGzipLogGivesTheRecordsBeforeTheCutThenSaysTruncated) {
  const auto full = TempPath("full.penalog.gz");
  const auto cut = TempPath("cut.penalog.gz");
  std::vector<sensors::SensorRecord> records;
  for (int i = 0; i < 100; ++i) records.push_back(testing::MakeScan(0.1 * i, MakeHeader().laser));
  testing::WriteLog(full, MakeHeader(), records);
  const std::string bytes = testing::ReadBytes(full);

  std::size_t most = 0;
  for (std::size_t size = bytes.size() / 4; size < bytes.size(); size += bytes.size() / 10) {
    testing::WriteBytes(cut, bytes.substr(0, size));
    MissionLogReader reader(cut);
    std::string error;
    const auto read = testing::ReadAll(reader, &error);
    for (std::size_t i = 0; i < read.size(); ++i) testing::ExpectSameRecord(records[i], read[i]);
    EXPECT_NE(error.find("truncated"), std::string::npos) << "cut at " << size << ": " << error;
    most = std::max(most, read.size());
  }
  // The writer's sync points (every second of log time) make most of a cut log readable.
  EXPECT_GT(most, records.size() / 2);
}

TEST(MissionLogErrors, EveryFlippedByteAfterThePreambleIsDetected) {
  const auto path = TempPath("flip.penalog");
  const std::vector<sensors::SensorRecord> records = testing::MakeOneOfEach(5.0);
  testing::WriteLog(path, MakeHeader(), records);
  const std::string bytes = testing::ReadBytes(path);
  const auto bad = TempPath("bad.penalog");
  for (std::size_t at = 12; at < bytes.size(); ++at) {
    std::string corrupt = bytes;
    corrupt[at] = static_cast<char>(corrupt[at] ^ 0x10);
    testing::WriteBytes(bad, corrupt);
    bool detected = false;
    try {
      MissionLogReader reader(bad);
      std::string error;
      testing::ReadAll(reader, &error);
      detected = !error.empty();
    } catch (const InputError&) {
      detected = true;
    }
    EXPECT_TRUE(detected) << "flipped byte " << at << " of " << bytes.size() << " went unnoticed";
  }
}

TEST(MissionLogErrors, FlippedByteInAScanNamesCrcMismatch) {
  const auto path = TempPath("crc.penalog");
  testing::WriteLog(path, MakeHeader(), testing::MakeOneOfEach(5.0));
  std::string bytes = testing::ReadBytes(path);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);  // inside scan 1
  testing::WriteBytes(path, bytes);
  MissionLogReader reader(path);
  std::string error;
  EXPECT_TRUE(testing::ReadAll(reader, &error).empty());
  EXPECT_NE(error.find(":1: record 1 at byte offset "), std::string::npos) << error;
  EXPECT_NE(error.find("CRC mismatch"), std::string::npos) << error;
}

TEST(MissionLogErrors, RejectsWrongMagic) {
  const auto path = TempPath("intel.clf");
  testing::WriteBytes(path, "# CARMEN log\nODOM 0 0 0 0 0 0 1.0 host 1.0\n");
  EXPECT_NE(OpenError(path).find("not a PeNa mission log (bad magic bytes)"), std::string::npos);
}

TEST(MissionLogErrors, RejectsUnknownMajorVersion) {
  const auto path = TempPath("v2.penalog");
  testing::WriteLog(path, MakeHeader(), {});
  std::string bytes = testing::ReadBytes(path);
  bytes[8] = 2;
  bytes[10] = 0;
  testing::WriteBytes(path, bytes);
  const std::string error = OpenError(path);
  EXPECT_NE(error.find("unsupported mission log format version 2.0"), std::string::npos) << error;
}

TEST(MissionLogErrors, RejectsEmptyAndMissingFiles) {
  const auto empty = TempPath("empty.penalog");
  testing::WriteBytes(empty, "");
  EXPECT_NE(OpenError(empty).find("empty file"), std::string::npos);
  EXPECT_NE(OpenError(TempPath("missing.penalog")).find("cannot open"), std::string::npos);
}

TEST(MissionLogErrors, WriterNamesThePathWhenItCannotCreateTheFile) {
  const auto path = TempPath("no-such-dir") / "x.penalog";
  try {
    MissionLogWriter writer(path, MakeHeader());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST(MissionLogErrors, WriterRejectsTimeGoingBackwardsWithinOneSensor) {
  MissionLogWriter writer(TempPath("back.penalog"), MakeHeader());
  writer.Write(sensors::GyroSample{2.0, 0.0});
  writer.Write(sensors::StrideSample{1.0, 0.7});  // another sensor may lag behind
  EXPECT_THROW(writer.Write(sensors::GyroSample{1.5, 0.0}), std::invalid_argument);
}

TEST(MissionLogErrors, WriterRejectsUnusableGeometryNamingFieldAndUnit) {
  MissionLogHeader header = MakeHeader();
  header.laser.max_range_m = -1.0;
  try {
    MissionLogWriter writer(TempPath("geometry.penalog"), header);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("header.laser.max_range_m must be in"),
              std::string::npos)
        << error.what();
  }
}

TEST(MissionLogErrors, WriterRejectsAnInterlaceOfNoSweepsNamingTheField) {
  MissionLogHeader header = MakeHeader();
  header.laser.interlace = 0;
  try {
    MissionLogWriter writer(TempPath("interlace.penalog"), header);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("header.laser.interlace must be in [1, 16], got 0"),
              std::string::npos)
        << error.what();
  }
}

TEST(MissionLogErrors, WriterRejectsANegativeSweepNamingFieldAndUnit) {
  MissionLogHeader header = MakeHeader();
  header.laser.sweep_s = -0.01;
  try {
    MissionLogWriter writer(TempPath("sweep.penalog"), header);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("header.laser.sweep_s must be in [0, 1] s"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::io
