#pragma once
// OUT/global_versions.csv: every global-map version the fusion published, one row
// `from,to,wall_ns` per delta, appended and flushed so it survives kill -9 (docs/fusion-service.md,
// "Persistence and restart"). Inputs are journaled before they are applied and the delta is
// logged after, so a fusion killed in between recovers versions nobody was sent. The restarted
// fusion publishes them with its startup snapshot, and CatchUp() writes the row that says so:
// the log stays one contiguous sequence of what readers could receive.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>

namespace pena::services {

class VersionsLog {
 public:
  // Opens `path` for appending (std::runtime_error naming it if it cannot be written) and reads
  // the last published version from the rows already there.
  explicit VersionsLog(const std::filesystem::path& path);

  void Append(std::uint64_t from_version, std::uint64_t to_version, std::int64_t wall_ns);
  // A restart recovered `recovered_version`: writes `last,recovered,wall_ns` if rows before it
  // end below it; returns the first version not published before, or nothing if none was missed.
  std::optional<std::uint64_t> CatchUp(std::uint64_t recovered_version, std::int64_t wall_ns);

  // The `to` of the last row (0 for an empty or new log).
  std::uint64_t last_version() const { return last_version_; }
  bool had_rows() const { return had_rows_; }

 private:
  std::ofstream out_;
  std::uint64_t last_version_ = 0;
  bool had_rows_ = false;
};

}  // namespace pena::services
