#include "operator_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace pena::services {
namespace {

// One whole line: correction_id,entity,operator,kind,from_stamp_s,x_m,y_m,theta_rad[,undoes];
// nullopt for a line of another shape (it still names an applied id).
std::optional<OperatorLogRecord> ParseLine(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  if (fields.size() < 8) return std::nullopt;
  OperatorLogRecord r;
  r.correction_id = fields[0];
  r.entity_id = fields[1];
  r.operator_id = fields[2];
  r.kind = fields[3];
  try {
    r.from_stamp_s = std::stod(fields[4]);
    r.corrected_from_wrong = {std::stod(fields[5]), std::stod(fields[6]), std::stod(fields[7])};
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (fields.size() > 8) r.undoes = fields[8];
  return r;
}

}  // namespace

OperatorLog::OperatorLog(std::filesystem::path path) : path_(std::move(path)) {
  {
    std::ifstream in(path_);
    std::string line;
    while (std::getline(in, line)) {
      // Only whole lines count: the last one may be torn by a crash (getline then hits EOF
      // without a newline).
      if (in.eof() || line.empty() || line[0] == '#') continue;
      std::optional<OperatorLogRecord> record = ParseLine(line);
      if (!record) {
        record = OperatorLogRecord{};
        record->correction_id = line.substr(0, line.find(','));
      }
      Remember(std::move(*record));
    }
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot open " + path_.string() + ": " + std::strerror(errno));
  }
  if (::lseek(fd_, 0, SEEK_END) == 0) {
    const std::string header =
        "# correction_id,entity,operator,kind,from_stamp_s,x_m,y_m,theta_rad,undoes\n";
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
                           r.kind + ',' + numbers + ',' + r.undoes + '\n';
  if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()) ||
      ::fsync(fd_) != 0) {
    throw std::runtime_error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  }
  Remember(r);
}

void OperatorLog::Remember(OperatorLogRecord record) {
  std::vector<std::string>& moves = in_force_[record.entity_id];
  if (record.kind == "undo") {
    std::erase(moves, record.undoes);
  } else if (!record.entity_id.empty()) {
    moves.push_back(record.correction_id);
  }
  records_[record.correction_id] = std::move(record);
}

const OperatorLogRecord* OperatorLog::Find(const std::string& correction_id) const {
  const auto it = records_.find(correction_id);
  return it == records_.end() ? nullptr : &it->second;
}

std::string OperatorLog::LastInForce(const std::string& entity_id) const {
  const auto it = in_force_.find(entity_id);
  return it == in_force_.end() || it->second.empty() ? std::string() : it->second.back();
}

}  // namespace pena::services
