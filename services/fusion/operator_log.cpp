#include "operator_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace pena::services {

OperatorLog::OperatorLog(std::filesystem::path path) : path_(std::move(path)) {
  {
    std::ifstream in(path_);
    std::string line;
    while (std::getline(in, line)) {
      // Only whole lines count: the last one may be torn by a crash (getline then hits EOF
      // without a newline).
      if (in.eof() || line.empty() || line[0] == '#') continue;
      ids_.insert(line.substr(0, line.find(',')));
    }
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot open " + path_.string() + ": " + std::strerror(errno));
  }
  if (::lseek(fd_, 0, SEEK_END) == 0) {
    const std::string header =
        "# correction_id,entity,operator,kind,from_stamp_s,x_m,y_m,theta_rad\n";
    if (::write(fd_, header.data(), header.size()) < 0) {
      throw std::runtime_error("cannot write " + path_.string() + ": " + std::strerror(errno));
    }
  }
}

OperatorLog::~OperatorLog() {
  if (fd_ >= 0) ::close(fd_);
}

void OperatorLog::Append(const OperatorLogRecord& r) {
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, "%.6f,%.9g,%.9g,%.12g", r.from_stamp_s,
                r.corrected_from_wrong.x_m, r.corrected_from_wrong.y_m,
                r.corrected_from_wrong.theta_rad);
  const std::string line = r.correction_id + ',' + r.entity_id + ',' + r.operator_id + ',' +
                           r.kind + ',' + numbers + '\n';
  if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()) ||
      ::fsync(fd_) != 0) {
    throw std::runtime_error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  }
  ids_.insert(r.correction_id);
}

}  // namespace pena::services
