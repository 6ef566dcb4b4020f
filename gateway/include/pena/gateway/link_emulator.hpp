#pragma once
// A one-way datagram link in simulated time (tests, experiments, and the delay/loss emulation
// that replaces netem where the kernel lacks it): a bottleneck of rate_bit_s with a byte-limited
// queue (like tc tbf), then a fixed delay, random loss, and outage windows in which every frame
// leaving the bottleneck is lost.

#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace pena::gateway {

// The link's properties; validated by EmulatedLink's constructor.
struct EmulatedLinkOptions {
  double rate_bit_s = 9600.0;           // 0: no bottleneck
  std::size_t overhead_bytes = 28;      // counted per frame on the bottleneck (IPv4 + UDP)
  std::size_t queue_limit_bytes = 4096; // frames arriving at a fuller queue are dropped (tail drop)
  double delay_s = 0.0;                 // one-way propagation delay
  double loss = 0.0;                    // probability that a frame is lost, in [0, 1)
  std::vector<std::pair<double, double>> outages;  // [start_s, end_s): nothing gets through
  std::uint64_t seed = 1;
};

// Counters of one direction.
struct EmulatedLinkStats {
  std::uint64_t frames_in = 0;
  std::uint64_t bytes_in = 0;         // frames plus overhead
  std::uint64_t dropped_queue = 0;
  std::uint64_t dropped_loss = 0;
  std::uint64_t dropped_outage = 0;
  std::uint64_t frames_out = 0;
};

class EmulatedLink {
 public:
  // Throws std::invalid_argument naming the field and unit for a bad option.
  explicit EmulatedLink(EmulatedLinkOptions options);
  // Offers a frame at now_s (time must not go backwards).
  void Send(std::string frame, double now_s);
  // The frames that have arrived by now_s, in order.
  std::vector<std::string> Receive(double now_s);
  const EmulatedLinkStats& stats() const { return stats_; }
  // True if now_s is inside an outage window.
  bool InOutage(double now_s) const;

 private:
  struct InFlight { double arrival_s; std::string frame; };
  struct Queued { double departure_s; std::size_t bytes; std::string frame; };
  void Advance(double now_s);

  EmulatedLinkOptions options_;
  std::mt19937_64 random_;
  std::deque<Queued> queue_;        // waiting for or in the bottleneck
  std::size_t queued_bytes_ = 0;
  double busy_until_s_ = 0.0;       // when the bottleneck finishes the last queued frame
  std::deque<InFlight> in_flight_;  // past the bottleneck, delayed
  EmulatedLinkStats stats_;
};

}  // namespace pena::gateway
