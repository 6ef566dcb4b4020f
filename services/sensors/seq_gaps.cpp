#include "seq_gaps.hpp"

#include <algorithm>
#include <stdexcept>

namespace pena::services {

SeqGaps::SeqGaps(SeqGapsOptions options) : options_(options) {
  if (options_.max_pending < 1) {
    throw std::invalid_argument("seq_gaps.max_pending must be >= 1 number, got 0");
  }
}

void SeqGaps::Saw(std::uint64_t seq) {
  if (seq == 0) return;
  highest_ = std::max(highest_, seq);
  if (seq <= contiguous_ || !pending_.insert(seq).second) {
    ++counts_.repeated_or_late;
    return;
  }
  Advance();
}

void SeqGaps::Advance() {
  while (!pending_.empty()) {
    const std::uint64_t next = *pending_.begin();
    if (next == contiguous_ + 1) {
      contiguous_ = next;
      pending_.erase(pending_.begin());
      continue;
    }
    // A hole below `next`: wait for it (topics arrive out of order between each other) unless
    // too many later numbers already arrived.
    if (pending_.size() <= options_.max_pending) return;
    (contiguous_ == 0 ? counts_.missed_at_start : counts_.missed) += next - contiguous_ - 1;
    contiguous_ = next - 1;
  }
}

SeqGapCounts SeqGaps::Counts() const {
  SeqGapCounts out = counts_;
  if (pending_.empty()) return out;
  std::uint64_t settled = contiguous_;
  if (contiguous_ == 0) {  // the start is still open: what lies below the lowest number
    settled = *pending_.begin() - 1;
    out.missed_at_start += settled;
  }
  out.missed += (highest_ - settled) - pending_.size();
  return out;
}

}  // namespace pena::services
