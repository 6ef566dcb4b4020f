#pragma once
// pena-fusion's record of the operator's rotations, translations and undos (paper section 4.1),
// one CSV line per correction in STATE_DIR/operator_corrections.csv, synced to disk before the
// correction is sent: after a restart (even kill -9) the durable operator topic delivers the
// same samples again, and the ids here say which were applied already, so none is lost and none
// is applied twice.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"

namespace pena::services {

// One applied operator move.
struct OperatorLogRecord {
  std::string correction_id;
  std::string entity_id;
  std::string operator_id;
  std::string kind;  // "rotate", "translate", "undo"
  double from_stamp_s = 0.0;
  geometry::Pose2 corrected_from_wrong;
  std::string undoes = {};  // kind "undo": the correction it takes back
};

class OperatorLog {
 public:
  // Opens (creates) the file and reads the ids it holds; a torn last line (a crash while
  // writing) is ignored. Throws std::runtime_error naming the file if it cannot be opened.
  explicit OperatorLog(std::filesystem::path path);
  ~OperatorLog();
  OperatorLog(const OperatorLog&) = delete;
  OperatorLog& operator=(const OperatorLog&) = delete;

  bool Contains(const std::string& correction_id) const { return records_.count(correction_id) > 0; }
  // The record with that id, or nullptr.
  const OperatorLogRecord* Find(const std::string& correction_id) const;
  // The id of the last move of `entity_id` still in force (not taken back by an undo); empty if
  // none. Undo goes from the end (paper section 4.1: the list is undone from its end).
  std::string LastInForce(const std::string& entity_id) const;
  // Appends and fsyncs; throws std::runtime_error if the write fails.
  void Append(const OperatorLogRecord& record);
  std::size_t size() const { return records_.size(); }

 private:
  void Remember(OperatorLogRecord record);

  std::filesystem::path path_;
  int fd_ = -1;
  std::map<std::string, OperatorLogRecord> records_;
  std::map<std::string, std::vector<std::string>> in_force_;  // entity -> its moves, in order
};

}  // namespace pena::services
