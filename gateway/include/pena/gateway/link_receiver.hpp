#pragma once
// The inbound half of a gateway endpoint: drops duplicates and stale items, puts map changes in
// version order (buffering early ones), and keeps what the peer must be told: acknowledgements of
// reliable items and this side's map versions (the ResyncSummary).

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "link.pb.h"
#include "pena/gateway/link_items.hpp"
#include "pena/gateway/map_fragments.hpp"

namespace pena::gateway {

// Limits of what the receiver buffers; validated by LinkReceiver's constructor.
struct ReceiverOptions {
  std::size_t max_early_deltas = 4096;   // per map: deltas waiting for a lost predecessor
  std::size_t max_selective_acks = 32;   // seqs listed beyond the cumulative ack
  double ack_delay_s = 0.2;              // an ack waits this long for a packet to ride on
  std::size_t max_update_bytes = 4 << 20;   // largest map update accepted in fragments
  std::size_t max_partial_bytes = 8 << 20;  // fragments held for incomplete updates (all maps)
};

// One received item with its reliable sequence number (0: not seq-acknowledged).
struct ReceivedItem {
  std::uint64_t seq = 0;
  DomainItem item;
};

class LinkReceiver {
 public:
  // Throws std::invalid_argument naming the field for a bad option.
  explicit LinkReceiver(ReceiverOptions options = {});

  // Takes decoded items of one accepted envelope; returns those to hand to the domain, in order.
  std::vector<DomainItem> Accept(std::vector<ReceivedItem> items, double now_s);
  // Takes one checked fragment (CheckFragment) with its seq; returns the serialised map update
  // (an Item) when this piece completes it. Duplicates are acknowledged and ignored.
  std::optional<std::string> AcceptFragment(std::uint64_t seq, const link::Fragment& fragment,
                                            double now_s);
  const FragmentAssembler& fragments() const { return assembler_; }
  std::size_t max_update_bytes() const { return options_.max_update_bytes; }
  // Forgets the peer's sequence numbers (it restarted and counts from 1 again).
  void OnPeerRestart(double now_s);

  // True if an ack or a summary is owed and has waited ack_delay_s for a packet to ride on.
  bool FeedbackDue(double now_s) const {
    return (ack_owed_ || summary_owed_) && now_s - owed_since_s_ >= options_.ack_delay_s;
  }
  bool ack_owed() const { return ack_owed_; }
  // The acknowledgement of everything received (the debt stays until ClearAck).
  link::Ack MakeAck() const;
  void ClearAck() { ack_owed_ = false; }
  // True if the peer should be sent this side's map versions.
  bool summary_owed() const { return summary_owed_; }
  void OweSummary(double now_s);
  // This side's map versions (the debt stays until ClearSummary).
  link::ResyncSummary MakeSummary(std::uint64_t session) const;
  void ClearSummary() { summary_owed_ = false; }
  // The version of a map held here (0 if unknown).
  std::uint64_t version(const std::string& map_id) const;

 private:
  struct InMap {
    std::uint64_t version = 0;
    std::map<std::uint64_t, MapChange> early;  // by from_version
  };

  bool FirstTime(std::uint64_t seq, double now_s);
  void AcceptMap(MapChange change, double now_s, std::vector<DomainItem>* out);
  void Owe(double now_s);

  ReceiverOptions options_;
  std::uint64_t cumulative_ = 0;
  std::set<std::uint64_t> beyond_;  // received seqs > cumulative_
  bool ack_owed_ = false;
  bool summary_owed_ = false;
  double owed_since_s_ = 0.0;
  std::map<std::string, double> pose_stamps_;              // newest delivered, by entity
  std::map<std::string, std::uint64_t> correction_versions_;  // newest delivered, by entity
  std::map<std::string, InMap> maps_;
  FragmentAssembler assembler_;
};

}  // namespace pena::gateway
