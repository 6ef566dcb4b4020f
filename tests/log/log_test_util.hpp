#pragma once
// Synthetic records and file helpers shared by the log tests.

#include <filesystem>
#include <string>
#include <vector>

#include "pena/io/input_error.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/sensors/record.hpp"

namespace pena::io::testing {

// A path in this test's own temporary directory (removed when the test process ends).
std::filesystem::path TempPath(const std::string& name);

// A header for a firefighter with a 361-beam, 180 deg laser.
MissionLogHeader MakeHeader();

// A 361-beam scan of a 4 m x 6 m room seen from its centre, with a few no-returns of every kind
// a source may give (infinity, NaN, 0, beyond max range).
sensors::LaserScan MakeScan(double stamp_s, const sensors::LaserGeometry& geometry);

// One record of every type, in stamp order, starting at `stamp_s`.
std::vector<sensors::SensorRecord> MakeOneOfEach(double stamp_s);

// Writes `records` after `header` to `path`.
void WriteLog(const std::filesystem::path& path, const MissionLogHeader& header,
              const std::vector<sensors::SensorRecord>& records);

// Reads records until the end (or until the reader throws, if `error` is given: then the message).
std::vector<sensors::SensorRecord> ReadAll(MissionLogReader& reader, std::string* error = nullptr);

std::string ReadBytes(const std::filesystem::path& path);
void WriteBytes(const std::filesystem::path& path, const std::string& bytes);

// Expects `actual` to equal `expected`: stamps and poses exactly, ranges within 1 mm, no-returns
// (by LaserScan::IsReturn) in the same beams.
void ExpectSameRecord(const sensors::SensorRecord& expected, const sensors::SensorRecord& actual);

}  // namespace pena::io::testing
