#pragma once
// Optional recording of what a daemon sent and received, one file per stream in a directory:
// line-map deltas and snapshots as length-prefixed records in the gateway's wire encoding
// (io::EncodeDelta / EncodeSnapshot, idl/line_map.proto): "<stream>.pbs"; everything else as
// CSV lines: "<stream>.csv". Layout in docs/services.md.

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "pena/line_map/map_delta.hpp"

namespace pena::services {

class Recorder {
 public:
  // Creates `directory`; throws std::runtime_error naming it if that fails.
  explicit Recorder(const std::filesystem::path& directory);

  // Appends a delta: 'D', uint32 little-endian size, EncodeDelta bytes.
  void Delta(const std::string& stream, const line_map::MapDelta& delta);
  // Appends a snapshot: 'S', uint32 little-endian size, EncodeSnapshot bytes.
  void Snapshot(const std::string& stream, const line_map::MapSnapshot& snapshot);
  // Appends one CSV line; `header` is written first when the file is new.
  void Csv(const std::string& stream, const std::string& header, const std::string& line);
  // Flushes every file.
  void Flush();

 private:
  std::ofstream& Open(const std::string& name, bool* created);
  void Framed(const std::string& stream, char tag, const std::string& bytes);

  std::filesystem::path directory_;
  std::map<std::string, std::ofstream> files_;
};

}  // namespace pena::services
