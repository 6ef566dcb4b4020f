#include "pena/io/log_source.hpp"

#include <algorithm>
#include <string_view>
#include <system_error>

#include "gz_line_reader.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/mission_log.hpp"

namespace pena::io {
namespace {

constexpr std::size_t kSniffBytes = 4096;

// True if the line starts with an upper-case message name (FLASER, PARAM, ROBOTLASER1, ...).
bool StartsWithMessageName(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && ((line[i] >= 'A' && line[i] <= 'Z') ||
                             (line[i] >= '0' && line[i] <= '9') || line[i] == '_')) {
    ++i;
  }
  const bool starts_upper = !line.empty() && line.front() >= 'A' && line.front() <= 'Z';
  return starts_upper && (i == line.size() || line[i] == ' ' || line[i] == '\t' ||
                          line[i] == '\r' || line[i] == '\n');
}

// A CARMEN log is text whose first non-comment line starts with an upper-case message name.
// Looking that far is enough to refuse binaries, CSV, JSON and Markdown with a clear error.
bool LooksLikeCarmen(const std::filesystem::path& path) {
  const std::string head = detail::ReadHead(path, kSniffBytes);
  if (head.find('\0') != std::string::npos) return false;
  std::size_t start = 0;
  while (start < head.size()) {
    const std::size_t end = std::min(head.find('\n', start), head.size());
    const std::string_view line = std::string_view(head).substr(start, end - start);
    const std::size_t text = line.find_first_not_of(" \t\r");
    if (text != std::string_view::npos && line[text] != '#') {
      return StartsWithMessageName(line.substr(text));
    }
    start = end + 1;
  }
  return true;  // empty or only comments (within the sniffed head): an empty log, not an error
}

}  // namespace

std::unique_ptr<LogSource> OpenLog(const std::filesystem::path& path, const ReadOptions& options) {
  // Check first so a missing file reads the same whichever format it would have had.
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError(path, 0, "no such file");
  if (std::filesystem::is_directory(path, error)) throw InputError(path, 0, "is a directory");
  if (IsMissionLog(path)) return std::make_unique<MissionLogReader>(path);
  if (!LooksLikeCarmen(path)) {
    throw InputError(path, 0, "format not recognised: neither a PeNa mission log nor a CARMEN log");
  }
  return OpenCarmenLog(path, options);
}

}  // namespace pena::io
