#include "pena/fusion/fusion_store.hpp"

#include <stdexcept>

#include "pena/fusion/fusion_codec.hpp"

namespace pena::fusion {
namespace {

FusionState Rebuild(const io::FusionJournal& journal, const FusionOptions& options,
                    FusionRecovery& recovery) {
  const io::JournalRecovery& found = journal.recovered();
  recovery.torn_tail = found.torn_tail;
  FusionState state(options);
  if (found.checkpoint_sequence) {
    const std::string name = journal.dir().string() + " checkpoint " +
                             std::to_string(*found.checkpoint_sequence);
    state = FusionState::FromCheckpoint(DecodeCheckpoint(found.checkpoint_payload, name), options);
    recovery.from_checkpoint = true;
    recovery.checkpoint_sequence = *found.checkpoint_sequence;
  }
  for (const io::JournalRecord& record : found.records) {
    const std::string name = journal.dir().string() + " record " + std::to_string(record.sequence);
    state.Handle(DecodeInput(record.payload, name));  // refusals repeat as they happened
    ++recovery.replayed;
  }
  return state;
}

const FusionStoreOptions& Validated(const FusionStoreOptions& options) {
  if (options.checkpoint_every < 1) {
    throw std::invalid_argument("fusion_store.checkpoint_every must be >= 1 (records), got 0");
  }
  ValidateFusionOptions(options.fusion);
  return options;
}

}  // namespace

FusionStore::FusionStore(const std::filesystem::path& dir, FusionStoreOptions options)
    : options_(Validated(options)),
      journal_(dir, options.journal),
      recovery_(),
      state_(Rebuild(journal_, options.fusion, recovery_)) {}

FusionOutput FusionStore::Handle(const FusionInput& input) {
  if (std::holds_alternative<Tick>(input) || std::holds_alternative<Publish>(input)) {
    FusionOutput output = state_.Handle(input);
    if (output.changed) {
      journal_.Append(EncodeInput(input));
      AfterAppend();
    }
    return output;
  }
  journal_.Append(EncodeInput(input));
  FusionOutput output = state_.Handle(input);
  AfterAppend();
  return output;
}

void FusionStore::AfterAppend() {
  if (++since_checkpoint_ >= options_.checkpoint_every) Checkpoint();
}

void FusionStore::Checkpoint() {
  journal_.WriteCheckpoint(EncodeCheckpoint(state_.Checkpoint()));
  since_checkpoint_ = 0;
}

}  // namespace pena::fusion
