#pragma once
// Which of a publisher's record numbers never arrived. pena-sensor-replay numbers its samples
// 1, 2, 3, ... across all sensor topics (`seq`), so a reader can tell a sample lost on the way, or
// an entity that joined late and missed the start of the stream, from a quiet sensor. DDS-free,
// tested alone.

#include <cstddef>
#include <cstdint>
#include <set>

namespace pena::services {

struct SeqGapsOptions {
  // Numbers held above the first hole while waiting for it to be filled. Topics arrive out of
  // order between each other, so a hole is not a loss until this many later numbers arrived;
  // bounds the memory a lost sample can cost. >= 1.
  std::size_t max_pending = 4096;
};

struct SeqGapCounts {
  std::uint64_t missed_at_start = 0;  // numbers below the lowest that arrived (joined late)
  std::uint64_t missed = 0;           // holes above it, given up or still open
  // Numbers that arrived twice (a restarted publisher counts from 1 again), or after their hole
  // had been given up.
  std::uint64_t repeated_or_late = 0;
};

class SeqGaps {
 public:
  // Throws std::invalid_argument naming max_pending.
  explicit SeqGaps(SeqGapsOptions options = {});

  // One sample numbered `seq` (the publisher counts from 1; 0 is taken as "unnumbered" and
  // ignored).
  void Saw(std::uint64_t seq);
  // Counts so far; holes still open count as missed (below the lowest number: at start).
  SeqGapCounts Counts() const;
  // The highest number seen (0 before the first).
  std::uint64_t highest() const { return highest_; }

 private:
  void Advance();

  SeqGapsOptions options_;
  // Every number up to here is settled: arrived, or given up as missed. 0 until the start is
  // settled (number 1 arrived, or the hole below the lowest number was given up).
  std::uint64_t contiguous_ = 0;
  std::uint64_t highest_ = 0;
  std::set<std::uint64_t> pending_;  // arrived above contiguous_, not yet settled
  SeqGapCounts counts_;
};

}  // namespace pena::services
