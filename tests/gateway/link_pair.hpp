#pragma once
// Two gateway endpoints joined by emulated links in simulated time (test helper).

#include <string>
#include <utility>
#include <vector>

#include "pena/gateway/domain_side.hpp"
#include "pena/gateway/link_emulator.hpp"
#include "pena/gateway/link_session.hpp"

namespace pena::gateway::testing {

// near <-> far, each direction its own EmulatedLink; Step advances both sessions by dt_s.
class LinkPair {
 public:
  LinkPair(LinkOptions near_options, LinkOptions far_options, EmulatedLinkOptions forward,
           EmulatedLinkOptions backward)
      : near_session(near_options, near), far_session(far_options, far),
        forward_link(forward), backward_link(backward) {}

  // Runs both endpoints from now_s to now_s + dt_s (inclusive end).
  void Step(double dt_s) {
    now_s += dt_s;
    near.set_clock(now_s);
    far.set_clock(now_s);
    for (std::string& frame : forward_link.Receive(now_s)) far_session.OnFrame(frame, now_s);
    for (std::string& frame : backward_link.Receive(now_s)) near_session.OnFrame(frame, now_s);
    for (std::string& frame : near_session.Poll(now_s)) {
      sent_forward.emplace_back(now_s, frame);
      forward_link.Send(std::move(frame), now_s);
    }
    for (std::string& frame : far_session.Poll(now_s)) backward_link.Send(std::move(frame), now_s);
  }
  // Steps until `until_s` in steps of dt_s.
  void RunUntil(double until_s, double dt_s = 0.01) {
    while (now_s < until_s - 1e-9) Step(dt_s);
  }

  InMemoryDomain near;
  InMemoryDomain far;
  LinkSession near_session;
  LinkSession far_session;
  EmulatedLink forward_link;
  EmulatedLink backward_link;
  std::vector<std::pair<double, std::string>> sent_forward;  // every frame near sent, with time
  double now_s = 0.0;
};

// Options for a fast, lossless, unconstrained pair (the budget is what a test varies).
inline EmulatedLinkOptions IdealLink() {
  EmulatedLinkOptions options;
  options.rate_bit_s = 0.0;
  options.delay_s = 0.05;
  return options;
}

inline LinkOptions Endpoint(std::uint64_t session) {
  LinkOptions options;
  options.session = session;
  return options;
}

}  // namespace pena::gateway::testing
