#pragma once
// The fusion with its persistence: every input is written to the journal before it is
// applied (write-ahead), and every checkpoint_every records the whole state is checkpointed. On
// construction the state is rebuilt from the directory (newest checkpoint plus the records after
// it), so a fusion killed with kill -9 resumes bit-identical and entities resynchronise by version.
// File access is io::FusionJournal's; this class only decides what to write when.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "pena/fusion/fusion_state.hpp"
#include "pena/io/fusion_journal.hpp"

namespace pena::fusion {

// Options of FusionStore.
struct FusionStoreOptions {
  FusionOptions fusion;
  io::FusionJournalOptions journal;
  std::size_t checkpoint_every = 500;  // journal records between checkpoints, >= 1
};

// What the recovery at construction found and did.
struct FusionRecovery {
  bool from_checkpoint = false;
  std::uint64_t checkpoint_sequence = 0;  // last record the checkpoint covered
  std::size_t replayed = 0;               // journal records applied after it
  std::string torn_tail;                  // io::JournalRecovery::torn_tail (empty: clean)
};

// A FusionState backed by a journal directory. Not thread-safe.
class FusionStore {
 public:
  // Opens or creates `dir` and rebuilds the state from it. Throws io::InputError for a corrupt
  // journal or checkpoint (naming file and byte), std::runtime_error for I/O failures,
  // std::invalid_argument for bad options.
  FusionStore(const std::filesystem::path& dir, FusionStoreOptions options = {});

  // Journals the input, then applies it. A Tick or Publish is journaled only if it changed the
  // state (it is applied first), so an idle fusion does not grow its journal.
  FusionOutput Handle(const FusionInput& input);
  // Writes a checkpoint now (e.g. at a clean shutdown).
  void Checkpoint();

  const FusionState& state() const { return state_; }
  const FusionRecovery& recovery() const { return recovery_; }
  std::uint64_t next_sequence() const { return journal_.next_sequence(); }

 private:
  void AfterAppend();

  FusionStoreOptions options_;
  io::FusionJournal journal_;
  FusionRecovery recovery_;  // before state_: the state's initialiser fills it
  FusionState state_;
  std::size_t since_checkpoint_ = 0;
};

}  // namespace pena::fusion
