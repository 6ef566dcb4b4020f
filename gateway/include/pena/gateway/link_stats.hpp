#pragma once
// Counters of one gateway endpoint (what the experiments report: bytes per class, losses).

#include <array>
#include <cstdint>

#include "pena/gateway/frame.hpp"

namespace pena::gateway {

// The message classes, in scheduling priority order (control first).
enum class ItemClass { kControl = 0, kAnnotation, kPose, kCorrection, kMap };
inline constexpr std::size_t kItemClassCount = 5;
// A short name for logs and JSON ("annotation").
const char* ToString(ItemClass item_class);

// Sent items of one class: count, encoded bytes inside envelopes, and how many were resends.
struct ClassCounters {
  std::uint64_t items = 0;
  std::uint64_t bytes = 0;
  std::uint64_t resent = 0;
};

struct LinkStats {
  std::array<ClassCounters, kItemClassCount> sent{};  // by ItemClass
  std::uint64_t frames_sent = 0;
  std::uint64_t frame_bytes_sent = 0;  // datagrams as written (frame; sealed: plus the seal)
  std::uint64_t seal_bytes_sent = 0;   // of those, the seal's header and tag (0 on an open link)
  std::uint64_t wire_bytes_sent = 0;   // plus the configured per-frame overhead (IP, UDP)
  std::uint64_t frames_received = 0;   // accepted
  std::array<std::uint64_t, kFrameStatusCount> rejected{};  // by FrameStatus (kOk unused)
  std::uint64_t poses_replaced = 0;    // a newer pose overwrote one not yet sent
  std::uint64_t deltas_pruned = 0;     // map deltas the peer confirmed (by version)
  std::uint64_t snapshots_queued = 0;  // whole maps sent because the peer's history had a gap
  std::uint64_t resyncs = 0;           // summaries received after a silence (outage, start)
  std::uint64_t updates_reassembled = 0;  // map updates received in fragments and made whole
  std::uint64_t reassembled_invalid = 0;  // of those, ones that did not decode (dropped)
  std::uint64_t rejected_total() const;
};

}  // namespace pena::gateway
