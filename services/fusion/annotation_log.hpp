#pragma once
// pena-fusion's record of the operator's marks as it relays them: every pena_dds::Annotation
// sample (a mark, its move, its retraction), CDR-serialised after a 4-byte length, in
// STATE_DIR/annotations.cdr, synced before it is relayed. A restarted fusion publishes the last
// sample of each annotation_id again (its relay writer is transient local), so a console that
// connects after a kill -9 of the fusion sees every mark, whoever made it and whether or not
// its console is still on the domain. A torn last record (a crash while writing) is ignored.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pena_dds/operator.h"

namespace pena::services {

class AnnotationLog {
 public:
  // Opens (creates) the file and reads its records. Throws std::runtime_error naming the file
  // if it cannot be opened, or the file and byte offset of a record that does not decode.
  explicit AnnotationLog(std::filesystem::path path);
  ~AnnotationLog();
  AnnotationLog(const AnnotationLog&) = delete;
  AnnotationLog& operator=(const AnnotationLog&) = delete;

  // Appends the sample and syncs, unless it is the same as the last one of its annotation_id
  // (an operator's durable sample delivered again after a restart); throws std::runtime_error
  // if the write fails.
  void Append(const pena_dds::Annotation& sample);
  // The last sample of every annotation_id, in the order the ids first came.
  std::vector<pena_dds::Annotation> Latest() const;
  std::size_t records() const { return records_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::size_t records_ = 0;
  std::vector<std::string> order_;                   // annotation ids, first come first
  std::map<std::string, std::string> latest_bytes_;  // annotation id -> its last record
};

}  // namespace pena::services
