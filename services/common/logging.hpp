#pragma once
// spdlog setup shared by the daemons: "[time] [daemon/entity] [level] message" on stderr, and
// optionally a file. Under systemd, with stderr connected to the journal, each stderr line
// starts with its syslog priority instead of the time ("<3>[pena-fusion] [error] ..."), which
// journald takes as the line's PRIORITY (systemd.exec, SyslogLevelPrefix=) and strips.

#include <spdlog/formatter.h>

#include <filesystem>
#include <memory>
#include <string>

namespace pena::services {

// Whether stderr is the journal: $JOURNAL_STREAM ("<device>:<inode>", set by systemd for a
// service whose output goes to the journal) names the file stderr is open on.
bool StderrIsJournal();

// The formatter of stderr lines for the journal: "<p>[name] [level] message", p the syslog
// priority of the level (trace and debug 7, info 6, warn 4, error 3, critical 2).
std::unique_ptr<spdlog::formatter> JournalFormatter();

// Sets the default logger. Throws std::invalid_argument for an unknown level name and
// std::runtime_error if the file cannot be opened.
void SetupLogging(const std::string& name, const std::string& level,
                  const std::filesystem::path& file = {});

}  // namespace pena::services
