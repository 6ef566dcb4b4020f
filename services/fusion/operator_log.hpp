#pragma once
// pena-fusion's record of the operator's rotations and translations (paper section 4.1), one
// CSV line per correction in STATE_DIR/operator_corrections.csv, synced to disk before the
// correction is sent: after a restart (even kill -9) the durable operator topic delivers the
// same samples again, and the ids here say which were applied already, so none is lost and none
// is applied twice.

#include <filesystem>
#include <set>
#include <string>

#include "pena/geometry/pose2.hpp"

namespace pena::services {

// One applied operator move.
struct OperatorLogRecord {
  std::string correction_id;
  std::string entity_id;
  std::string operator_id;
  std::string kind;  // "rotate", "translate"
  double from_stamp_s = 0.0;
  geometry::Pose2 corrected_from_wrong;
};

class OperatorLog {
 public:
  // Opens (creates) the file and reads the ids it holds; a torn last line (a crash while
  // writing) is ignored. Throws std::runtime_error naming the file if it cannot be opened.
  explicit OperatorLog(std::filesystem::path path);
  ~OperatorLog();
  OperatorLog(const OperatorLog&) = delete;
  OperatorLog& operator=(const OperatorLog&) = delete;

  bool Contains(const std::string& correction_id) const { return ids_.count(correction_id) > 0; }
  // Appends and fsyncs; throws std::runtime_error if the write fails.
  void Append(const OperatorLogRecord& record);
  std::size_t size() const { return ids_.size(); }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::set<std::string> ids_;
};

}  // namespace pena::services
