#pragma once
// Map updates too large for the room left in a packet (docs/gateway.md, "Fragments"). The sender
// cuts such an update into pieces sized to whatever room each packet has after the higher
// classes (link::Fragment: bytes of the serialised Item), so a big delta or snapshot never waits
// for an empty packet behind a steady stream of poses, and a map larger than one frame can cross
// at all. Each piece carries a seq, is acknowledged like an annotation and resent on its own timer;
// the receiver applies the update once it holds every byte.

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "link.pb.h"

namespace pena::gateway {

// Resend state of one reliable item or piece.
struct ResendTimer {
  double last_sent_s = 0.0;
  double timeout_s = 0.0;  // 0 after a resync: due at once
  int sends = 0;
  bool Due(double now_s) const { return sends == 0 || now_s - last_sent_s >= timeout_s; }
};

// One reliable map update on its way out: sent whole while it fits a packet, else in pieces.
class OutgoingUpdate {
 public:
  // `item` is the update's Item (body: map, seq 0); `group` names its pieces on the link.
  OutgoingUpdate(const link::Item& item, std::uint64_t group);

  const link::Item& item() const { return item_; }
  const std::string& bytes() const { return bytes_; }
  std::uint64_t group() const { return group_; }
  // True once any piece went out: from then on it travels in pieces only.
  bool fragmented() const { return fragmented_; }
  // Resend timer of the update sent whole.
  ResendTimer& whole_timer() { return whole_timer_; }
  const ResendTimer& whole_timer() const { return whole_timer_; }

  // A range of the serialised bytes, with the timer of its last send (sends 0: never sent).
  struct Piece {
    std::uint32_t offset = 0;
    std::uint32_t length = 0;
    std::uint64_t seq = 0;  // 0: never sent
    bool acked = false;
    ResendTimer timer;
  };
  // The pieces to send now, in offset order: never sent, or unacknowledged past their timer.
  std::vector<Piece> DuePieces(double now_s) const;
  // Bytes [offset, offset + length) went out now as `seq`; `offset` starts a due piece and
  // `length` does not exceed it (the rest of it keeps its state). Returns the sent piece's timer
  // state before this send (sends > 0: a resend).
  ResendTimer MarkSent(std::uint32_t offset, std::uint32_t length, std::uint64_t seq,
                       double now_s, double first_timeout_s, double max_timeout_s);
  // Marks acknowledged the pieces whose seq the peer acknowledged.
  void Ack(const link::Ack& ack);
  // True if it was sent completely at least once (whole, or every piece).
  bool SentCompletely() const;
  // True if every piece was acknowledged at least `stall_s` ago (fragmented only): the peer
  // holds every byte but did not confirm the version, so it dropped them (buffer limits).
  bool Stalled(double now_s, double stall_s) const;
  // Starts over under a new group: the peer lost its pieces (it restarted or dropped them).
  void Restart(std::uint64_t group);
  // Makes every unacknowledged piece (and the whole update) due at once.
  void DueNow();

 private:
  link::Item item_;
  std::string bytes_;
  std::uint64_t group_;
  bool fragmented_ = false;
  ResendTimer whole_timer_;
  std::vector<Piece> pieces_;  // cover [0, bytes_.size()) in offset order
};

// Checks a received fragment against the limits; "" if sound, else what is wrong.
std::string CheckFragment(const link::Fragment& fragment, std::size_t max_update_bytes);

// The receiver's half: collects the pieces of each group until the update is whole.
class FragmentAssembler {
 public:
  // max_buffered_bytes bounds the pieces held for incomplete updates, and max_incomplete their
  // number; the oldest incomplete update is dropped beyond either (its sender restarts it when
  // the version stays unconfirmed).
  explicit FragmentAssembler(std::size_t max_buffered_bytes, std::size_t max_incomplete = 256);
  // Takes one checked piece; returns the serialised update when this piece completes it.
  std::optional<std::string> Add(const link::Fragment& fragment);
  // Forgets everything (the peer restarted: its group numbers start over).
  void Clear();
  std::size_t buffered_bytes() const { return buffered_bytes_; }
  std::size_t incomplete() const { return partial_.size(); }
  std::uint64_t dropped() const { return dropped_; }

 private:
  struct Partial {
    std::uint32_t total_bytes = 0;
    std::map<std::uint32_t, std::string> pieces;  // by offset, not overlapping
    std::size_t held_bytes = 0;
    std::uint64_t created = 0;
  };
  void Insert(Partial& partial, std::uint32_t offset, std::string_view data);
  void Evict(std::uint64_t keep_group);
  void Forget(std::uint64_t group);

  std::size_t max_buffered_bytes_;
  std::size_t max_incomplete_;
  std::size_t buffered_bytes_ = 0;
  std::uint64_t next_created_ = 0;
  std::uint64_t dropped_ = 0;
  std::map<std::uint64_t, Partial> partial_;  // by group
  std::map<std::uint64_t, std::uint64_t> by_age_;  // created -> group, oldest first
  std::set<std::uint64_t> done_;              // recently completed groups: late pieces ignored
  std::deque<std::uint64_t> done_order_;
};

}  // namespace pena::gateway
