#include "recorder.hpp"

#include <array>
#include <stdexcept>

#include "pena/io/line_map_codec.hpp"

namespace pena::services {

Recorder::Recorder(const std::filesystem::path& directory) : directory_(directory) {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) {
    throw std::runtime_error(directory_.string() + ": cannot create the recording directory: " +
                             error.message());
  }
}

std::ofstream& Recorder::Open(const std::string& name, bool* created) {
  auto it = files_.find(name);
  *created = it == files_.end();
  if (*created) {
    const std::filesystem::path path = directory_ / name;
    it = files_.emplace(name, std::ofstream(path, std::ios::binary | std::ios::trunc)).first;
    if (!it->second) throw std::runtime_error(path.string() + ": cannot open for writing");
  }
  return it->second;
}

void Recorder::Framed(const std::string& stream, char tag, const std::string& bytes) {
  bool created = false;
  std::ofstream& out = Open(stream + ".pbs", &created);
  const auto size = static_cast<std::uint32_t>(bytes.size());
  const std::array<char, 5> header{tag, static_cast<char>(size & 0xFFu),
                                   static_cast<char>((size >> 8) & 0xFFu),
                                   static_cast<char>((size >> 16) & 0xFFu),
                                   static_cast<char>((size >> 24) & 0xFFu)};
  out.write(header.data(), header.size());
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void Recorder::Delta(const std::string& stream, const line_map::MapDelta& delta) {
  Framed(stream, 'D', io::EncodeDelta(delta));
}

void Recorder::Snapshot(const std::string& stream, const line_map::MapSnapshot& snapshot) {
  Framed(stream, 'S', io::EncodeSnapshot(snapshot));
}

void Recorder::Csv(const std::string& stream, const std::string& header,
                   const std::string& line) {
  bool created = false;
  std::ofstream& out = Open(stream + ".csv", &created);
  if (created) out << header << '\n';
  out << line << '\n';
}

void Recorder::OpenSensorLog(const io::MissionLogHeader& header) {
  sensor_log_ = std::make_unique<io::MissionLogWriter>(directory_ / "sensors.penalog", header);
}

void Recorder::Sensor(const sensors::SensorRecord& record) {
  if (sensor_log_) sensor_log_->Write(record);
}

void Recorder::Flush() {
  for (auto& [name, file] : files_) file.flush();
}

void Recorder::Close() {
  Flush();
  if (sensor_log_) {
    sensor_log_->Close();
    sensor_log_.reset();
  }
  files_.clear();
}

}  // namespace pena::services
