#include "versions_log.hpp"

#include <stdexcept>
#include <string>

namespace pena::services {
namespace {

// The `to` of the last well-formed row; a row is written whole by one flush, so anything else
// (a header, a foreign line) is skipped rather than trusted.
std::optional<std::uint64_t> LastTo(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::optional<std::uint64_t> last;
  for (std::string line; std::getline(in, line);) {
    const std::size_t first = line.find(',');
    const std::size_t second = line.find(',', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    try {
      std::size_t used = 0;
      const std::string to = line.substr(first + 1, second - first - 1);
      const std::uint64_t value = std::stoull(to, &used);
      if (used == to.size()) last = value;
    } catch (const std::exception&) {
      continue;
    }
  }
  return last;
}

}  // namespace

VersionsLog::VersionsLog(const std::filesystem::path& path) {
  const std::optional<std::uint64_t> last = LastTo(path);
  had_rows_ = last.has_value();
  last_version_ = last.value_or(0);
  out_.open(path, std::ios::app);
  if (!out_) throw std::runtime_error("cannot write " + path.string());
}

void VersionsLog::Append(std::uint64_t from_version, std::uint64_t to_version,
                         std::int64_t wall_ns) {
  out_ << from_version << ',' << to_version << ',' << wall_ns << '\n';
  out_.flush();
  last_version_ = to_version;
  had_rows_ = true;
}

std::optional<std::uint64_t> VersionsLog::CatchUp(std::uint64_t recovered_version,
                                                  std::int64_t wall_ns) {
  // A new log (a fresh output directory on a recovered state) has no sequence to continue.
  if (!had_rows_ || recovered_version <= last_version_) return std::nullopt;
  const std::uint64_t first_missed = last_version_ + 1;
  Append(last_version_, recovered_version, wall_ns);
  return first_missed;
}

}  // namespace pena::services
