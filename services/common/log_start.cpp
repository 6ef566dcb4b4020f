#include "log_start.hpp"

#include <utility>
#include <variant>

namespace pena::services {

LogStart ReadLogStart(io::LogSource& source, const std::filesystem::path& input,
                      const std::string& entity_id, std::optional<sensors::EntityKind> kind) {
  LogStart start;
  while (auto record = source.Next()) {
    start.records.push_back(std::move(*record));
    if (std::holds_alternative<sensors::LaserScan>(start.records.back())) break;
  }
  const io::LogDescription& description = source.description();
  start.kind = kind.value_or(description.kind.value_or(sensors::EntityKind::kRobot));
  const std::string file_name = input.filename().string();
  start.entity_id = !entity_id.empty()               ? entity_id
                    : !description.entity_id.empty() ? description.entity_id
                                                     : file_name.substr(0, file_name.find('.'));
  return start;
}

std::optional<sensors::SensorRecord> NextRecord(std::vector<sensors::SensorRecord>& read_ahead,
                                                std::size_t& taken, io::LogSource& source) {
  if (taken < read_ahead.size()) return std::move(read_ahead[taken++]);
  return source.Next();
}

}  // namespace pena::services
