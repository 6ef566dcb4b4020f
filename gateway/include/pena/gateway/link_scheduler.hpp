#pragma once
// The outbound half of a gateway endpoint (docs/gateway.md, "Scheduler"): what is waiting for the
// link and in which order it goes. Alarms and annotations first (reliable), then the latest pose
// of each entity (a newer pose replaces an unsent one; never queued), then corrections (reliable,
// newest per entity), then map deltas (never dropped: kept until the peer's summary shows its map
// at or past their version, resent on timeout; a whole snapshot if the peer's history has a gap).
// A map update that does not fit the room left in a packet goes in pieces cut to that room
// (map_fragments.hpp), so it never waits behind the poses for an empty packet.

#include <cstdint>
#include <array>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "link.pb.h"
#include "pena/gateway/link_items.hpp"
#include "pena/gateway/link_stats.hpp"
#include "pena/gateway/map_fragments.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::gateway {

// Retransmission timing; validated by LinkScheduler's constructor.
struct SchedulerOptions {
  double retransmit_timeout_s = 3.0;      // first resend of an unacknowledged item
  double max_retransmit_timeout_s = 12.0; // the timeout doubles per resend up to this
  std::size_t min_piece_bytes = 32;       // a map piece carries at least this many bytes
  double fragment_stall_s = 24.0;         // every piece acked this long, version unconfirmed:
                                          // the peer dropped them; send the update again
};

// One piece of a map update put into an envelope (map_fragments.hpp).
struct PieceRef {
  std::string map_id;
  bool snapshot = false;
  std::uint64_t to_version = 0;  // deltas: which one
  std::uint32_t offset = 0;
  std::uint32_t length = 0;
  std::uint64_t seq = 0;
};

// The items Fill put into an envelope; Commit marks them sent once the frame goes out.
struct Selection {
  std::vector<std::uint64_t> annotation_seqs;
  std::vector<std::string> pose_entities;
  std::vector<std::string> correction_entities;
  std::vector<std::string> snapshot_maps;
  std::vector<std::pair<std::string, std::uint64_t>> deltas;  // map id, to_version
  std::vector<PieceRef> pieces;
  std::array<ClassCounters, kItemClassCount> counters{};
  bool full = false;  // stopped because the next item did not fit
  bool map_waiting = false;  // map data is due that this envelope had no room for
  std::size_t size() const;
};

class LinkScheduler {
 public:
  // Throws std::invalid_argument naming the field and unit for a bad option.
  explicit LinkScheduler(SchedulerOptions options = {});

  // Queues an item from the local domain (maps: a delta that does not follow is dropped and
  // counted; the domain must then offer a snapshot).
  void Offer(DomainItem item);
  // Appends due items in priority order while the envelope stays within max_bytes (one item may
  // exceed it if `oversized_ok` and nothing was added yet). Changes nothing until Commit.
  Selection Fill(link::Envelope* envelope, std::size_t max_bytes, bool oversized_ok,
                 double now_s);
  // Marks the selection sent at now_s (timeouts start, resends counted in `stats`).
  void Commit(const Selection& selection, double now_s, LinkStats* stats);

  // Drops annotations and corrections the peer acknowledged.
  void OnAck(const link::Ack& ack);
  // Takes the peer's map versions (its acknowledgement of map updates); maps it does not list
  // are at version 0. Prunes confirmed deltas, queues snapshots where its history has a gap.
  void OnPeerSummary(const link::ResyncSummary& summary, LinkStats* stats);
  // Makes every unacknowledged item due now (after a resync: the peer is back).
  void ResendAllNow();
  // The peer restarted: the pieces it acknowledged are gone; map updates start over.
  void OnPeerRestart();

  // Waiting reliable items (not yet acknowledged), for tests and stats.
  std::size_t pending_annotations() const { return annotations_.size(); }
  std::size_t pending_corrections() const;
  std::size_t pending_deltas() const;
  // Map deltas dropped on Offer because they did not follow the map's version.
  std::size_t rejected_offers() const { return rejected_offers_; }
  // Poses overwritten by a newer one before they were sent.
  std::uint64_t replaced_poses() const { return replaced_poses_; }

 private:
  using Timer = ResendTimer;
  struct PendingAnnotation { DomainItem item; Timer timer; };  // Annotation or OperatorCorrection
  struct PendingCorrection { Correction correction; std::uint64_t seq = 0; bool acked = false; Timer timer; };
  struct PoseSlot { PoseUpdate pose; bool sent = false; };
  struct PendingDelta {
    std::uint64_t from_version = 0;
    std::uint64_t to_version = 0;
    OutgoingUpdate update;
    std::uint64_t order = 0;
  };
  struct OutMap {
    line_map::LineMap mirror;  // the sender's map, to build snapshots
    std::deque<PendingDelta> pending;
    std::uint64_t peer_version = 0;
    std::optional<OutgoingUpdate> snapshot;  // due until the peer holds snapshot_version
    bool reset = false;
    std::uint64_t snapshot_version = 0;  // the version of that snapshot
  };
  class Filler;

  void OfferMap(MapChange change);
  void QueueSnapshot(const std::string& map_id, OutMap& map, bool reset);
  // Adds `update` whole if it fits, else as many of its due pieces as the envelope has room for;
  // false once the envelope is full.
  bool AddUpdate(Filler& filler, const OutgoingUpdate& update, PieceRef ref, double now_s,
                 Selection* selection, bool* whole) const;
  OutgoingUpdate* Find(const PieceRef& ref);
  void Sent(Timer& timer, double now_s, ClassCounters& counters) const;
  void CheckPeerMap(const std::string& map_id, OutMap& map, LinkStats* stats);

  SchedulerOptions options_;
  std::uint64_t next_seq_ = 1;
  std::uint64_t next_order_ = 0;
  std::uint64_t next_group_ = 1;
  std::map<std::uint64_t, PendingAnnotation> annotations_;  // by seq
  std::map<std::string, PoseSlot> poses_;
  std::map<std::string, PendingCorrection> corrections_;
  std::map<std::string, OutMap> maps_;
  std::size_t rejected_offers_ = 0;
  std::uint64_t replaced_poses_ = 0;
};

}  // namespace pena::gateway
