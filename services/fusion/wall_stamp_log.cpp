#include "wall_stamp_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace pena::services {

WallStampLog::WallStampLog(std::filesystem::path path) : path_(std::move(path)) {
  {
    std::ifstream in(path_);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      // Only whole lines count: the last one may be torn by a crash (no newline before EOF).
      if (in.eof() || line.empty() || line[0] == '#') continue;
      // The entity id may hold anything but a newline: the two numbers are the last fields.
      const std::size_t stamp_at = line.rfind(',');
      const std::size_t id_at = stamp_at == std::string::npos || stamp_at == 0
                                    ? std::string::npos
                                    : line.rfind(',', stamp_at - 1);
      std::int64_t id = 0;
      double stamp_s = 0.0;
      const char* id_end = line.data() + stamp_at;
      const char* stamp_end = line.data() + line.size();
      if (id_at == std::string::npos ||
          std::from_chars(line.data() + id_at + 1, id_end, id).ptr != id_end ||
          std::from_chars(line.data() + stamp_at + 1, stamp_end, stamp_s).ptr != stamp_end ||
          !std::isfinite(stamp_s)) {
        throw std::runtime_error(path_.string() + ":" + std::to_string(number) +
                                 ": not 'entity,segment_id,stamp_s': '" + line + "'");
      }
      stamps_[line.substr(0, id_at)].emplace(id, stamp_s);
    }
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot open " + path_.string() + ": " + std::strerror(errno));
  }
  if (::lseek(fd_, 0, SEEK_END) == 0) {
    const std::string header = "# entity,segment_id,stamp_s\n";
    if (::write(fd_, header.data(), header.size()) < 0) {
      throw std::runtime_error("cannot write " + path_.string() + ": " + std::strerror(errno));
    }
  }
}

WallStampLog::~WallStampLog() {
  if (fd_ >= 0) ::close(fd_);
}

void WallStampLog::Append(const std::string& entity_id,
                          const std::vector<std::pair<std::int64_t, double>>& walls) {
  if (walls.empty()) return;
  std::string lines;
  for (const auto& [id, stamp_s] : walls) {
    char numbers[64];
    std::snprintf(numbers, sizeof numbers, ",%lld,%.6f\n", static_cast<long long>(id), stamp_s);
    lines += entity_id + numbers;
  }
  // Into the kernel, the durability of the store's journal (JournalDurability::kFlush): a kill -9
  // loses none, a power loss may lose what the journal loses too.
  if (::write(fd_, lines.data(), lines.size()) != static_cast<ssize_t>(lines.size())) {
    throw std::runtime_error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  }
  std::map<std::int64_t, double>& stamps = stamps_[entity_id];
  for (const auto& [id, stamp_s] : walls) stamps.emplace(id, stamp_s);
}

}  // namespace pena::services
