#pragma once
// The fusion service's persistence on disk (docs/fusion.md): a directory holding an
// append-only journal of opaque records (every input the fusion received, in order) and periodic
// checkpoints (the whole state at one record). After a crash the newest checkpoint plus the
// journal records after it rebuild the state. Each record is framed like the mission log: length,
// payload and a CRC-32, so a record torn by the crash is detected and dropped with a message.
// The payloads are the fusion module's business (fusion_codec.hpp); this file only moves bytes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pena::io {

// The journal and checkpoint file format version written, and the only one read.
inline constexpr std::uint32_t kFusionJournalFormatVersion = 1;

// How hard Append pushes a record to disk before returning.
enum class JournalDurability {
  kFlush,  // into the kernel: survives a crash of the process (kill -9), not of the machine
  kFsync,  // fdatasync: survives power loss too (slower)
};

// Options of FusionJournal.
struct FusionJournalOptions {
  JournalDurability durability = JournalDurability::kFlush;
};

// One journal record: its sequence number (1, 2, ... without gaps) and payload.
struct JournalRecord {
  std::uint64_t sequence = 0;
  std::string payload;
};

// What was on disk when the journal was opened.
struct JournalRecovery {
  std::optional<std::uint64_t> checkpoint_sequence;  // last record the checkpoint covers
  std::string checkpoint_payload;
  std::vector<JournalRecord> records;  // after the checkpoint, in order, contiguous
  std::string torn_tail;  // empty, or what was dropped: "path: torn record at byte N (M bytes)"
};

// A journal directory opened for recovery and appending. Not thread-safe.
class FusionJournal {
 public:
  // Opens `dir` (created if missing) and reads what it holds. Throws InputError naming the file
  // and byte offset for corruption other than a torn last record (bad magic or version, a bad
  // record followed by more data, missing records), std::runtime_error for I/O failures.
  explicit FusionJournal(const std::filesystem::path& dir, FusionJournalOptions options = {});
  ~FusionJournal();
  FusionJournal(const FusionJournal&) = delete;
  FusionJournal& operator=(const FusionJournal&) = delete;

  // What the directory held at open.
  const JournalRecovery& recovered() const;
  // Appends one record; returns its sequence number. Throws std::runtime_error on I/O failure.
  std::uint64_t Append(std::string_view payload);
  // Stores `payload` as the checkpoint covering every record appended so far (written to a
  // temporary file, synced and renamed, so a crash leaves the old or the new one), starts a new
  // journal file and deletes files older than the previous checkpoint.
  void WriteCheckpoint(std::string_view payload);
  // The sequence number the next Append gets.
  std::uint64_t next_sequence() const;
  const std::filesystem::path& dir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::io
