#pragma once
// Small helpers of the io tests: temp files with given content, plain or gzip.

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "pena/io/log_source.hpp"
#include "pena/sensors/record.hpp"
#include "scoped_temp_dir.hpp"
#include "test_data.hpp"

namespace pena::io::testing {

// A path in this test's own temporary directory (removed when the test process ends).
inline std::filesystem::path TempPath(const std::string& name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = pena::testing::ProcessTempDir() /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return dir / name;
}

inline std::filesystem::path WriteText(const std::string& name, const std::string& content) {
  const std::filesystem::path path = TempPath(name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

inline std::filesystem::path WriteGzip(const std::string& name, const std::string& content) {
  const std::filesystem::path path = TempPath(name);
  gzFile file = gzopen(path.c_str(), "wb");
  EXPECT_NE(file, nullptr);
  gzwrite(file, content.data(), static_cast<unsigned>(content.size()));
  gzclose(file);
  return path;
}

// All records of a log, in order.
inline std::vector<sensors::SensorRecord> ReadAll(LogSource& source) {
  std::vector<sensors::SensorRecord> records;
  while (std::optional<sensors::SensorRecord> record = source.Next()) {
    records.push_back(std::move(*record));
  }
  return records;
}

// A FLASER line with `n` ranges all equal to `range`, poses zero, at `stamp`.
inline std::string FlaserLine(std::size_t n, const std::string& range, const std::string& stamp) {
  std::string line = "FLASER " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) line += " " + range;
  return line + " 1.5 -2 0.25 1.4 -2.1 0.2 " + stamp + " host " + stamp + "\n";
}

}  // namespace pena::io::testing
