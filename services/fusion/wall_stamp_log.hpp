#pragma once
// pena-fusion's record of when each entity mapped its walls: per entity and local segment id,
// the mission stamp of the delta (or snapshot) that first brought the wall. An operator's
// rotation or translation from a stamp on moves the walls an entity mapped after that stamp
// (docs/fusion-service.md), so a restarted fusion must know them as well as the one before it:
// one CSV line per wall in STATE_DIR/wall_stamps.csv, written (into the kernel, like the store's
// journal: a kill -9 loses none) before the delta is applied. A torn last line is ignored.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace pena::services {

class WallStampLog {
 public:
  // Opens (creates) the file and reads what it holds. Throws std::runtime_error naming the file
  // if it cannot be opened, or the file and line if a whole line is not "entity,id,stamp_s".
  explicit WallStampLog(std::filesystem::path path);
  ~WallStampLog();
  WallStampLog(const WallStampLog&) = delete;
  WallStampLog& operator=(const WallStampLog&) = delete;

  // Appends the walls' stamps (segment id, mission seconds) of one entity in one write; throws
  // std::runtime_error if that fails.
  void Append(const std::string& entity_id,
              const std::vector<std::pair<std::int64_t, double>>& walls);
  // Per entity, per segment id: the stamp first recorded (a wall recorded again keeps it).
  const std::map<std::string, std::map<std::int64_t, double>>& stamps() const { return stamps_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::map<std::string, std::map<std::int64_t, double>> stamps_;
};

}  // namespace pena::services
