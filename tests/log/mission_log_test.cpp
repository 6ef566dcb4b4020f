// Round trips through the native mission log: every record type, the header, compression.
#include "pena/io/mission_log.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <numbers>

#include "log_test_util.hpp"
#include "pena/io/carmen.hpp"
#include "pena_log.pb.h"
#include "test_data.hpp"

namespace pena::io {
namespace {

using testing::MakeHeader;
using testing::MakeOneOfEach;
using testing::TempPath;

TEST(MissionLog, RoundTripsEveryRecordType) {
  const auto path = TempPath("every.penalog");
  const auto records = MakeOneOfEach(1.7e9 + 0.123456);  // epoch stamps must come back exact
  testing::WriteLog(path, MakeHeader(), records);

  MissionLogReader reader(path);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    SCOPED_TRACE("record " + std::to_string(i));
    testing::ExpectSameRecord(records[i], read[i]);
  }
  EXPECT_FALSE(reader.Next().has_value());  // the end stays the end
}

TEST(MissionLog, RoundTripsHeaderAndDescribesTheLog) {
  const auto path = TempPath("header.penalog");
  MissionLogHeader header = MakeHeader();
  header.kind = sensors::EntityKind::kRobot;
  header.entity_id = "robot2";
  header.mission = "Bürogebäude, 2. OG";  // UTF-8 text survives
  testing::WriteLog(path, header, {});

  MissionLogReader reader(path);
  const MissionLogHeader& got = reader.header();
  EXPECT_EQ(got.format_version, kMissionLogFormatVersion);
  EXPECT_EQ(got.mission, header.mission);
  EXPECT_EQ(got.entity_id, "robot2");
  EXPECT_EQ(got.kind, sensors::EntityKind::kRobot);
  EXPECT_EQ(got.laser.angle_min_rad, header.laser.angle_min_rad);
  EXPECT_EQ(got.laser.angle_increment_rad, header.laser.angle_increment_rad);
  EXPECT_EQ(got.laser.max_range_m, header.laser.max_range_m);
  EXPECT_EQ(got.laser_height_m, header.laser_height_m);
  EXPECT_EQ(got.producer, header.producer);
  EXPECT_EQ(reader.description().format, "pena-log");
  EXPECT_EQ(reader.description().entity_id, "robot2");
  EXPECT_EQ(reader.description().kind, sensors::EntityKind::kRobot);
  EXPECT_EQ(reader.description().mission, header.mission);
  EXPECT_EQ(reader.description().path, path);
  EXPECT_FALSE(reader.Next().has_value());
}

TEST(MissionLog, HeaderWithoutLaserLetsEveryScanCarryItsGeometry) {
  const auto path = TempPath("nolaser.penalog");
  MissionLogHeader header = MakeHeader();
  header.laser = {};
  const std::vector<sensors::SensorRecord> records = {testing::MakeScan(1.0, {-1.0, 0.01, 20.0}),
                                                      testing::MakeScan(2.0, {-1.5, 0.02, 10.0})};
  testing::WriteLog(path, header, records);

  MissionLogReader reader(path);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), 2u);
  testing::ExpectSameRecord(records[0], read[0]);
  testing::ExpectSameRecord(records[1], read[1]);
}

// A laser that takes time over its scan (docs/odometry.md, "Scan deskew"): the header's sweep and
// interlace and a scan's own survive, and 0 (the simulator's instantaneous scans) stays 0.
TEST(MissionLog, RoundTripsTheLasersSweepTimeAndInterlace) {
  const auto path = TempPath("sweep.penalog");
  MissionLogHeader header = MakeHeader();
  header.laser.sweep_s = 1.0 / 150.0;
  header.laser.interlace = 2;
  const std::vector<sensors::SensorRecord> records = {
      testing::MakeScan(1.0, header.laser), testing::MakeScan(2.0, {-1.5, 0.02, 10.0, 0.025, 4}),
      testing::MakeScan(3.0, {-1.5, 0.02, 10.0, 0.0})};
  testing::WriteLog(path, header, records);

  MissionLogReader reader(path);
  EXPECT_EQ(reader.header().laser.sweep_s, 1.0 / 150.0);
  EXPECT_EQ(reader.header().laser.interlace, 2);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), 3u);
  for (std::size_t i = 0; i < read.size(); ++i) testing::ExpectSameRecord(records[i], read[i]);
}

TEST(MissionLog, GzNameWritesCompressedStreamThatReadsTheSame) {
  const auto plain = TempPath("run.penalog");
  const auto packed = TempPath("run.penalog.gz");
  std::vector<sensors::SensorRecord> records;
  for (int i = 0; i < 200; ++i) records.push_back(testing::MakeScan(0.1 * i, MakeHeader().laser));
  testing::WriteLog(plain, MakeHeader(), records);
  testing::WriteLog(packed, MakeHeader(), records);

  const std::string bytes = testing::ReadBytes(packed);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1Fu);  // gzip magic
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8Bu);
  EXPECT_LT(bytes.size(), std::filesystem::file_size(plain));
  EXPECT_TRUE(IsMissionLog(packed));
  MissionLogReader reader(packed);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) testing::ExpectSameRecord(records[i], read[i]);
}

TEST(MissionLog, ScansTakeLessThanTwoBytesPerBeam) {
  const auto path = TempPath("size.penalog");
  std::vector<sensors::SensorRecord> records;
  for (int i = 0; i < 100; ++i) records.push_back(testing::MakeScan(0.1 * i, MakeHeader().laser));
  testing::WriteLog(path, MakeHeader(), {});
  const auto empty_size = std::filesystem::file_size(path);
  testing::WriteLog(path, MakeHeader(), records);
  const double per_scan =
      static_cast<double>(std::filesystem::file_size(path) - empty_size) / 100.0;
  // 361 beams: absolute millimetres would need 2 bytes each (722); deltas need far less.
  EXPECT_LT(per_scan, 2.0 * 361);
  ::testing::Test::RecordProperty("bytes_per_361_beam_scan", std::to_string(per_scan));
}

TEST(MissionLog, IsMissionLogTellsNativeLogsFromText) {
  const auto native = TempPath("a.penalog");
  testing::WriteLog(native, MakeHeader(), {});
  const auto carmen = TempPath("a.clf");
  testing::WriteBytes(carmen, "FLASER 3 1.0 2.0 3.0 0 0 0 0 0 0 1.0 host 1.0\n");
  const auto empty = TempPath("empty.penalog");
  testing::WriteBytes(empty, "");
  EXPECT_TRUE(IsMissionLog(native));
  EXPECT_FALSE(IsMissionLog(carmen));
  EXPECT_FALSE(IsMissionLog(empty));
  EXPECT_FALSE(IsMissionLog(TempPath("missing.penalog")));
  EXPECT_FALSE(IsMissionLog(native.parent_path()));  // a directory
}

// Frames `message` as the doc says: varint size, bytes, CRC-32 of both (little-endian).
std::string Frame(const google::protobuf::MessageLite& message) {
  std::string frame;
  std::uint64_t size = message.ByteSizeLong();
  do {
    frame.push_back(static_cast<char>((size & 0x7Fu) | (size >= 0x80u ? 0x80u : 0u)));
    size >>= 7;
  } while (size > 0);
  frame += message.SerializeAsString();
  const uLong crc =
      crc32(0L, reinterpret_cast<const Bytef*>(frame.data()), static_cast<uInt>(frame.size()));
  for (int i = 0; i < 4; ++i) frame.push_back(static_cast<char>((crc >> (8 * i)) & 0xFFu));
  return frame;
}

TEST(MissionLog, SkipsRecordTypesFromANewerMinorVersion) {
  const auto path = TempPath("newer.penalog");
  testing::WriteLog(path, MakeHeader(), {sensors::GyroSample{1.0, 0.5}});
  // A later writer adds a record type (oneof field 40) that this reader does not know.
  log::Record future;
  future.GetReflection()->MutableUnknownFields(&future)->AddLengthDelimited(40, "thermal camera");
  log::Record stride;
  stride.mutable_stride()->set_stamp_s(2.0);
  stride.mutable_stride()->set_length_m(0.8);
  testing::WriteBytes(path, testing::ReadBytes(path) + Frame(future) + Frame(stride));

  MissionLogReader reader(path);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(std::get<sensors::GyroSample>(read[0]).yaw_rate_rad_s, 0.5);
  EXPECT_EQ(std::get<sensors::StrideSample>(read[1]).length_m, 0.8);
}

TEST(MissionLog, AcceptsANewerMinorVersion) {
  const auto path = TempPath("minor.penalog");
  testing::WriteLog(path, MakeHeader(), {sensors::GyroSample{1.0, 0.5}});
  std::string bytes = testing::ReadBytes(path);
  bytes[10] = 7;  // minor version 7: only additions, which this reader may ignore
  testing::WriteBytes(path, bytes);
  MissionLogReader reader(path);
  EXPECT_EQ(testing::ReadAll(reader).size(), 1u);
}

TEST(MissionLog, ReaderRejectsTimeGoingBackwardsNamingTheRecord) {
  const auto path = TempPath("back.penalog");
  testing::WriteLog(path, MakeHeader(), {sensors::GyroSample{2.0, 0.5}});
  log::Record earlier;
  earlier.mutable_gyro()->set_stamp_s(1.0);
  testing::WriteBytes(path, testing::ReadBytes(path) + Frame(earlier));
  MissionLogReader reader(path);
  std::string error;
  EXPECT_EQ(testing::ReadAll(reader, &error).size(), 1u);
  EXPECT_NE(error.find(":2: record 2 at byte offset "), std::string::npos) << error;
  EXPECT_NE(error.find("gyro stamp 1 s goes back in time"), std::string::npos) << error;
}

// The uncompressed size of a gzip (or plain) file.
std::size_t InflatedSize(const std::filesystem::path& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  std::vector<char> buffer(1 << 16);
  std::size_t total = 0;
  for (int got = 0; (got = gzread(file, buffer.data(), 1 << 16)) > 0;) total += std::size_t(got);
  gzclose(file);
  return total;
}

TEST(MissionLog, RealScansRoundTripAndTakeLessSpaceThanCarmen) {
  // 1988 scans of 361 beams, FLASER lines only: the file is exactly the scans as CARMEN text.
  const std::filesystem::path carmen = pena::testing::DataPath("freiburg/mit-csail.clf.gz");
  std::vector<sensors::SensorRecord> records;
  const auto source = OpenCarmenLog(carmen);
  while (auto record = source->Next()) records.push_back(std::move(*record));
  ASSERT_GT(records.size(), 1000u);
  MissionLogHeader header = MakeHeader();
  header.laser = std::get<sensors::LaserScan>(records.front()).geometry;
  const auto plain = TempPath("mit.penalog");
  const auto packed = TempPath("mit.penalog.gz");
  testing::WriteLog(plain, header, records);
  testing::WriteLog(packed, header, records);

  MissionLogReader reader(packed);
  const auto read = testing::ReadAll(reader);
  ASSERT_EQ(read.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) testing::ExpectSameRecord(records[i], read[i]);
  const auto scans = static_cast<double>(records.size());
  const double text = static_cast<double>(InflatedSize(carmen)) / scans;
  const double text_gz = static_cast<double>(std::filesystem::file_size(carmen)) / scans;
  const double native = static_cast<double>(std::filesystem::file_size(plain)) / scans;
  const double native_gz = static_cast<double>(std::filesystem::file_size(packed)) / scans;
  EXPECT_LT(native, 0.3 * text);
  EXPECT_LT(native_gz, text_gz);
  ::testing::Test::RecordProperty("carmen_bytes_per_scan", std::to_string(text));
  ::testing::Test::RecordProperty("carmen_gz_bytes_per_scan", std::to_string(text_gz));
  ::testing::Test::RecordProperty("native_bytes_per_scan", std::to_string(native));
  ::testing::Test::RecordProperty("native_gz_bytes_per_scan", std::to_string(native_gz));
}

}  // namespace
}  // namespace pena::io
