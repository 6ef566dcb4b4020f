#pragma once
// One gateway endpoint's link logic (docs/gateway.md), independent of sockets and clocks: Poll
// turns what the domain produced into frames within the bit budget, OnFrame turns received frames
// into deliveries. Two sessions joined by any datagram link (UDP, the emulated link in tests)
// keep each other's picture: alarms, latest poses, corrections and line maps.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pena/gateway/domain_side.hpp"
#include "pena/gateway/frame.hpp"
#include "pena/gateway/link_crypto.hpp"
#include "pena/gateway/link_receiver.hpp"
#include "pena/gateway/link_scheduler.hpp"
#include "pena/gateway/link_stats.hpp"
#include "pena/gateway/token_bucket.hpp"

namespace pena::gateway {

// Budget and timing of one endpoint; validated by LinkSession's constructor.
struct LinkOptions {
  double budget_bit_s = 8640.0;        // token rate: keep below the link's rate (90 % of 9.6 kbit/s)
  double burst_bits = 8.0 * 1200.0;    // bucket capacity; must hold one full packet
  std::size_t packet_bytes = 480;      // target envelope size (one frame)
  std::size_t overhead_bytes = 28;     // per frame below the link frame (IPv4 20 + UDP 8)
  double min_packet_interval_s = 0.2;  // a packet that is not full waits this long since the last
  double heartbeat_s = 1.0;            // send at least this often (an empty envelope if need be)
  double outage_timeout_s = 3.5;       // peer silent this long: outage, only probes go out
  double probe_interval_s = 1.0;       // resync requests while the peer is silent
  bool compress = true;                // deflate a frame's payload when that makes it smaller
  std::uint64_t session = 0;           // this endpoint's session id; 0: random
  std::optional<LinkKey> key;          // seal every datagram with it (docs/security.md); none: open
  SealOptions seal;                    // replay window and clock limit of a sealed link
  FrameLimits limits;
  SchedulerOptions scheduler;
  ReceiverOptions receiver;
};

class LinkSession {
 public:
  // Throws std::invalid_argument naming the field and unit for a bad option. `domain` must
  // outlive the session.
  LinkSession(LinkOptions options, DomainSide& domain);

  // Takes the domain's new items and returns the datagrams to send now (possibly none): link
  // frames, sealed if the link has a key.
  std::vector<std::string> Poll(double now_s);
  // Handles one received datagram; a rejected one (status and message for the caller to log)
  // changes nothing.
  FrameResult OnFrame(std::string_view bytes, double now_s);

  // True if the peer was heard within outage_timeout_s.
  bool peer_alive(double now_s) const;
  // When the peer was last heard (the clock of OnFrame; < 0 before the first frame).
  double last_heard_s() const { return last_heard_s_ < -1e8 ? -1.0 : last_heard_s_; }
  const LinkOptions& options() const { return options_; }
  const LinkStats& stats() const;
  const LinkScheduler& scheduler() const { return scheduler_; }
  const LinkReceiver& receiver() const { return receiver_; }
  std::uint64_t session() const { return options_.session; }
  // True if datagrams are sealed (the options held a key).
  bool sealed() const { return seal_ != nullptr; }

 private:
  std::optional<std::string> BuildFrame(double now_s);
  bool AddControl(link::Envelope* envelope, double now_s) const;
  FrameResult Reject(FrameStatus status, std::string message);
  void OnPeerSession(std::uint64_t session, double now_s);
  std::string DecodeItems(const link::Envelope& envelope, std::vector<ReceivedItem>* items) const;
  void AcceptFragments(const link::Envelope& envelope, std::vector<ReceivedItem>* items, double now_s);

  LinkOptions options_;
  DomainSide& domain_;
  std::unique_ptr<LinkSeal> seal_;
  LinkScheduler scheduler_;
  LinkReceiver receiver_;
  TokenBucket bucket_;
  mutable LinkStats stats_;
  std::uint64_t next_packet_seq_ = 1;
  double last_sent_s_ = -1e9;
  double last_heard_s_ = -1e9;
  double next_probe_s_ = -1e9;
  bool awaiting_resync_ = true;  // heard nothing yet, or nothing since an outage
  std::uint64_t peer_session_ = 0;
};

}  // namespace pena::gateway
