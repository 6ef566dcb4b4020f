// The daemons' logging under systemd: lines on a stderr that is the journal carry their syslog
// priority as journald's "<p>" prefix; elsewhere they keep the time stamp.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "logging.hpp"

namespace pena::services {
namespace {

std::string Format(spdlog::formatter& formatter, spdlog::level::level_enum level) {
  const spdlog::details::log_msg msg("pena-fusion", level, "text");
  spdlog::memory_buf_t out;
  formatter.format(msg, out);
  return std::string(out.data(), out.size());
}

TEST(Logging, JournalLinesStartWithTheLevelsSyslogPriority) {
  const auto formatter = JournalFormatter();
  EXPECT_EQ(Format(*formatter, spdlog::level::critical), "<2>[pena-fusion] [critical] text\n");
  EXPECT_EQ(Format(*formatter, spdlog::level::err), "<3>[pena-fusion] [error] text\n");
  EXPECT_EQ(Format(*formatter, spdlog::level::warn), "<4>[pena-fusion] [warning] text\n");
  EXPECT_EQ(Format(*formatter, spdlog::level::info), "<6>[pena-fusion] [info] text\n");
  EXPECT_EQ(Format(*formatter, spdlog::level::debug), "<7>[pena-fusion] [debug] text\n");
  EXPECT_EQ(Format(*formatter, spdlog::level::trace), "<7>[pena-fusion] [trace] text\n");
}

// Runs `log` with stderr redirected to a file, JOURNAL_STREAM naming that file when `journal`
// (or another file when not); returns what reached the file.
template <class Log>
std::string CaptureStderr(bool journal, Log log) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("pena_logging_test_" + std::to_string(getpid()));
  const int file = open(path.c_str(), O_CREAT | O_TRUNC | O_WRONLY, 0600);
  EXPECT_GE(file, 0);
  struct stat status {};
  EXPECT_EQ(fstat(file, &status), 0);
  const std::string stream = std::to_string(status.st_dev) + ":" +
                             std::to_string(journal ? status.st_ino : status.st_ino + 1);
  std::fflush(stderr);
  const int saved = dup(2);
  dup2(file, 2);
  close(file);
  setenv("JOURNAL_STREAM", stream.c_str(), 1);
  const auto previous = spdlog::default_logger();
  log();
  spdlog::default_logger()->flush();
  spdlog::set_default_logger(previous);
  unsetenv("JOURNAL_STREAM");
  dup2(saved, 2);
  close(saved);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return text.str();
}

TEST(Logging, DaemonLinesCarryTheirPriorityOnlyWhenStderrIsTheJournal) {
  const auto log = [] {
    SetupLogging("pena-entity/ff1", "info");
    spdlog::error("lost the link");
    spdlog::warn("slow scan");
    spdlog::info("started");
    spdlog::debug("not shown");
  };
  EXPECT_EQ(CaptureStderr(true, log),
            "<3>[pena-entity/ff1] [error] lost the link\n"
            "<4>[pena-entity/ff1] [warning] slow scan\n"
            "<6>[pena-entity/ff1] [info] started\n");
  const std::string plain = CaptureStderr(false, log);
  EXPECT_EQ(plain.rfind("[20", 0), 0U) << plain;  // the time stamp, no priority
  EXPECT_NE(plain.find("] [pena-entity/ff1] [error] lost the link\n"), std::string::npos) << plain;
  EXPECT_EQ(plain.find('<'), std::string::npos) << plain;
}

TEST(Logging, WithoutJournalStreamStderrIsNotTheJournal) {
  unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(StderrIsJournal());
}

}  // namespace
}  // namespace pena::services
